// A Catch2 matcher for the exception family: the message contains every given part.
#pragma once

#include <catch2/catch.hpp>
#include <initializer_list>
#include <string>
#include <vector>

namespace dtsl::test {

class MessageContains : public Catch::MatcherBase<std::exception> {
 public:
  MessageContains(std::initializer_list<std::string> parts) : parts_(parts) {}
  bool match(const std::exception& e) const override {
    const std::string what = e.what();
    for (const std::string& p : parts_)
      if (what.find(p) == std::string::npos) return false;
    return true;
  }
  std::string describe() const override {
    std::string s = "message contains";
    for (const std::string& p : parts_) s += " '" + p + "'";
    return s;
  }

 private:
  std::vector<std::string> parts_;
};

}  // namespace dtsl::test
