#include "src/lexer.hpp"

#include <gtest/gtest.h>

namespace rover::apl::sequencer::internal {
namespace {

std::vector<TokenKind> Kinds(const std::vector<Token>& ts) {
  std::vector<TokenKind> out;
  for (const auto& t : ts) out.push_back(t.kind);
  return out;
}

TEST(Lexer, TokensWithLinesAndColumns) {
  std::vector<LexError> errors;
  const auto ts = Lex("DRIVE ARC curvature=0.5  # arc\n  IF tilt >= 15 deg\n", &errors);
  EXPECT_TRUE(errors.empty());
  using K = TokenKind;
  EXPECT_EQ(Kinds(ts), (std::vector<K>{K::kIdent, K::kIdent, K::kIdent, K::kAssign, K::kNumber,
                                       K::kNewline, K::kIdent, K::kIdent, K::kGe, K::kNumber,
                                       K::kIdent, K::kNewline, K::kNewline, K::kEnd}));
  EXPECT_EQ(ts[2].text, "curvature");
  EXPECT_EQ(ts[2].pos, (SourcePos{1, 11}));
  EXPECT_EQ(ts[4].pos, (SourcePos{1, 21}));
  EXPECT_DOUBLE_EQ(ts[4].number, 0.5);
  EXPECT_EQ(ts[6].pos, (SourcePos{2, 3}));
  EXPECT_EQ(ts[9].pos, (SourcePos{2, 14}));
}

TEST(Lexer, NumbersSignsExponentsAndGluedUnits) {
  std::vector<LexError> errors;
  const auto ts = Lex("-0.5 +.25 1e3 2.5E-2 30cm 0.1m/s last.fault", &errors);
  EXPECT_TRUE(errors.empty());
  EXPECT_DOUBLE_EQ(ts[0].number, -0.5);
  EXPECT_DOUBLE_EQ(ts[1].number, 0.25);
  EXPECT_DOUBLE_EQ(ts[2].number, 1000.0);
  EXPECT_DOUBLE_EQ(ts[3].number, 0.025);
  EXPECT_DOUBLE_EQ(ts[4].number, 30.0);
  EXPECT_EQ(ts[5].kind, TokenKind::kIdent);
  EXPECT_EQ(ts[5].text, "cm");
  EXPECT_EQ(ts[7].text, "m/s");
  EXPECT_EQ(ts[8].text, "last.fault");
}

TEST(Lexer, OperatorsAndPunctuation) {
  std::vector<LexError> errors;
  const auto ts = Lex("( , ) = == != < <= > >=", &errors);
  using K = TokenKind;
  EXPECT_EQ(Kinds(ts), (std::vector<K>{K::kLParen, K::kComma, K::kRParen, K::kAssign, K::kEq,
                                       K::kNe, K::kLt, K::kLe, K::kGt, K::kGe, K::kNewline,
                                       K::kEnd}));
}

TEST(Lexer, BadCharactersAreErrorsWithTheirPosition) {
  std::vector<LexError> errors;
  const auto ts = Lex("STOP\nWAIT 5 s; @ é!", &errors);
  ASSERT_EQ(errors.size(), 4u);
  EXPECT_EQ(errors[0].pos, (SourcePos{2, 9}));
  EXPECT_EQ(errors[0].message, "unexpected character ';'");
  EXPECT_EQ(errors[1].message, "unexpected character '@'");
  EXPECT_EQ(errors[2].message, "unexpected character 'é'");  // one whole UTF-8 character
  EXPECT_EQ(errors[3].message, "unexpected character '!'");
  EXPECT_EQ(Describe(ts.back()), "end of input");
}

}  // namespace
}  // namespace rover::apl::sequencer::internal
