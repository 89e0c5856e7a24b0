// "Did you mean": the closest known name within a third of the name's length, nothing otherwise.
#include <catch2/catch.hpp>

#include "framework/core/suggest.hpp"

using namespace dtsl;

TEST_CASE("edit distance counts insertions, deletions, substitutions and adjacent swaps") {
  CHECK(edit_distance("", "") == 0);
  CHECK(edit_distance("abc", "") == 3);
  CHECK(edit_distance("", "abc") == 3);
  CHECK(edit_distance("dtsl", "dtsl") == 0);
  CHECK(edit_distance("dtls", "dtsl") == 1);       // a swap
  CHECK(edit_distance("reconstuct", "reconstruct") == 1);  // a deletion
  CHECK(edit_distance("kitten", "sitting") == 3);
  CHECK(edit_distance("abc", "cab") == 2);
  // Symmetric.
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{{"depth", "dpeth"}, {"run", "urn"}, {"list", "lists"}})
    CHECK(edit_distance(a, b) == edit_distance(b, a));
}

TEST_CASE("the closest name is suggested only when it is a plausible typo") {
  const std::vector<std::string> commands = {"run", "report", "table", "merge", "reconstruct", "list", "help"};
  CHECK(closest_name("reconstuct", commands) == "reconstruct");
  CHECK(closest_name("lst", commands) == "list");
  CHECK(closest_name("frobnicate", commands).empty());
  CHECK(closest_name("x", commands).empty());
  CHECK(did_you_mean("tabel", commands) == " (did you mean 'table'?)");
  CHECK(did_you_mean("zzzzzz", commands).empty());
  CHECK(closest_name("anything", {}).empty());
  // Ties go to the first known name.
  CHECK(closest_name("ab", {"aa", "bb"}) == "aa");
}
