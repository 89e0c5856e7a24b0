// "Did you mean ...?" for unknown names (commands, options, keys, plugins): the closest known name by
// edit distance, when it is close enough to be a plausible typo.
#pragma once

#include <string>
#include <vector>

namespace dtsl {

/// The edit distance of `a` and `b` (insertions, deletions, substitutions and swaps of adjacent
/// characters each cost 1; the optimal string alignment distance).
std::size_t edit_distance(const std::string& a, const std::string& b);

/// The known name closest to `name`, or "" when none is within a third of its length (at least 1, at
/// most 3 edits), so unrelated names are not suggested. Ties go to the first in `known`.
std::string closest_name(const std::string& name, const std::vector<std::string>& known);

/// " (did you mean 'x'?)" for the closest name, or "" when there is none.
std::string did_you_mean(const std::string& name, const std::vector<std::string>& known);

}  // namespace dtsl
