// Helpers shared by the sequencer's tests: parse a text that must be valid, or collect the
// errors of one that must not.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "rover/apl/sequencer/parser.hpp"

namespace rover::apl::sequencer::testing {

/// The sequence of a text that must parse; fails the test (and returns an empty one) otherwise.
inline Sequence MustParse(const std::string& text, const ParseOptions& options = {}) {
  ParseReport r = ParseSequenceText(text, options);
  EXPECT_TRUE(r.ok()) << FormatErrors(r, options.source) << "in:\n" << text;
  return r.ok() ? *r.sequence : Sequence{};
}

/// The errors of a text that must not parse.
inline std::vector<ParseError> ErrorsOf(const std::string& text,
                                        const ParseOptions& options = {}) {
  ParseReport r = ParseSequenceText(text, options);
  EXPECT_FALSE(r.ok()) << "parsed although it should not:\n" << text;
  EXPECT_FALSE(r.sequence.has_value());
  return r.errors;
}

/// The only statement of a one-command text.
inline CommandCall CallOf(const std::string& line) {
  Sequence s = MustParse(line + "\n");
  EXPECT_EQ(s.statements.size(), 1u);
  if (s.statements.empty()) return {};
  return s.statements[0].command;
}

}  // namespace rover::apl::sequencer::testing
