// Registers every plugin of dtsl with its registry. Call once before creating plugins by name.
#pragma once

namespace dtsl {
void register_all_plugins();
}
