// Crash-safe file writing: write to "<path>.tmp-<pid>", then rename over <path>. A reader never sees a
// half-written file, and a killed process leaves at most a stray .tmp file, never a corrupt result.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace dtsl {

/// Calls `write` on a binary stream to a temporary file next to `path`, then renames it to `path`.
/// On any failure (including an exception from `write`) the temporary file is removed and a
/// FileError naming `path` is thrown.
void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

/// A temporary path next to `path` for writers that need a file name (e.g. PCL's); pair with
/// commit_temporary().
std::string temporary_path_for(const std::string& path);
void commit_temporary(const std::string& temporary, const std::string& path);

/// Removes, under `dir` (recursively), the temporary files ("<name>.tmp-<pid>") of processes that no
/// longer run: what a killed writer left behind. A live writer's temporary is kept. Returns how many
/// were removed; a missing `dir` is not an error.
std::size_t remove_stale_temporaries(const std::string& dir);

}  // namespace dtsl
