#pragma once
// The sequence language's tokens (private to the library; parser.cpp is its user).
//
//   identifier  letter or '_', then letters, digits, '_' and '.'; a '/' between letters joins
//               a unit ("m/s")
//   number      [+-] digits [. digits] [e [+-] digits]  or  [+-] . digits
//   operators   ( ) , = == != < <= > >=
//   newline     ends a statement; '#' starts a comment that runs to the end of the line
//
// Columns are 1-based byte offsets in the line.

#include <string>
#include <string_view>
#include <vector>

#include "rover/apl/sequencer/sequence.hpp"

namespace rover::apl::sequencer::internal {

enum class TokenKind {
  kIdent,
  kNumber,
  kLParen,
  kRParen,
  kComma,
  kAssign,  // =
  kEq,      // ==
  kNe,      // !=
  kLt,
  kLe,
  kGt,
  kGe,
  kNewline,
  kEnd,     // end of input
  kBad,     // a character the language does not use (text says which)
};

struct Token {
  TokenKind kind = TokenKind::kEnd;
  std::string text;    // as written
  double number = 0.0; // kNumber
  SourcePos pos;
};

struct LexError {
  SourcePos pos;
  std::string message;
};

/// Tokens of `text`, always ending with kNewline then kEnd. Bad characters become kBad tokens
/// and an error each.
std::vector<Token> Lex(std::string_view text, std::vector<LexError>* errors);

/// A readable name of a token for messages: "'foo'", "end of line", "'('".
std::string Describe(const Token& t);

}  // namespace rover::apl::sequencer::internal
