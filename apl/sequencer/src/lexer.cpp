#include "lexer.hpp"

#include <cctype>
#include <cstdlib>

namespace rover::apl::sequencer::internal {
namespace {

bool IsIdentStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IsIdentChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
}
bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

class Lexer {
 public:
  Lexer(std::string_view text, std::vector<LexError>* errors) : text_(text), errors_(errors) {}

  std::vector<Token> Run() {
    std::vector<Token> out;
    while (i_ < text_.size()) {
      const char c = text_[i_];
      if (c == '\n') {
        out.push_back(Make(TokenKind::kNewline, "\n"));
        Advance(1);
        ++line_;
        line_start_ = i_;
      } else if (c == ' ' || c == '\t' || c == '\r') {
        Advance(1);
      } else if (c == '#') {
        while (i_ < text_.size() && text_[i_] != '\n') Advance(1);
      } else if (IsIdentStart(c)) {
        out.push_back(Ident());
      } else if (IsDigit(c) || StartsNumber()) {
        out.push_back(Number());
      } else {
        out.push_back(Punct());
      }
    }
    out.push_back(Make(TokenKind::kNewline, "\n"));
    out.push_back(Make(TokenKind::kEnd, ""));
    return out;
  }

 private:
  SourcePos Pos() const {
    return {line_, static_cast<int>(i_ - line_start_) + 1};
  }
  Token Make(TokenKind kind, std::string t) const { return Token{kind, std::move(t), 0.0, Pos()}; }
  void Advance(std::size_t n) { i_ += n; }
  char At(std::size_t k) const { return k < text_.size() ? text_[k] : '\0'; }

  // A sign or a '.' that starts a number: "-1", "+.5", ".5".
  bool StartsNumber() const {
    const char c = At(i_);
    std::size_t k = i_;
    if (c == '+' || c == '-') ++k;
    if (IsDigit(At(k))) return true;
    return At(k) == '.' && IsDigit(At(k + 1));
  }

  Token Ident() {
    Token t = Make(TokenKind::kIdent, "");
    const std::size_t start = i_;
    while (IsIdentChar(At(i_)) ||
           (At(i_) == '/' && IsIdentStart(At(i_ + 1)) && i_ > start)) {
      Advance(1);
    }
    t.text = std::string(text_.substr(start, i_ - start));
    return t;
  }

  Token Number() {
    Token t = Make(TokenKind::kNumber, "");
    const std::size_t start = i_;
    if (At(i_) == '+' || At(i_) == '-') Advance(1);
    while (IsDigit(At(i_))) Advance(1);
    if (At(i_) == '.') {
      Advance(1);
      while (IsDigit(At(i_))) Advance(1);
    }
    if ((At(i_) == 'e' || At(i_) == 'E') &&
        (IsDigit(At(i_ + 1)) ||
         ((At(i_ + 1) == '+' || At(i_ + 1) == '-') && IsDigit(At(i_ + 2))))) {
      Advance(2);
      while (IsDigit(At(i_))) Advance(1);
    }
    t.text = std::string(text_.substr(start, i_ - start));
    t.number = std::strtod(t.text.c_str(), nullptr);
    return t;
  }

  Token Punct() {
    const char c = At(i_);
    const char n = At(i_ + 1);
    auto two = [&](TokenKind k) {
      Token t = Make(k, std::string(text_.substr(i_, 2)));
      Advance(2);
      return t;
    };
    auto one = [&](TokenKind k) {
      Token t = Make(k, std::string(1, c));
      Advance(1);
      return t;
    };
    switch (c) {
      case '(': return one(TokenKind::kLParen);
      case ')': return one(TokenKind::kRParen);
      case ',': return one(TokenKind::kComma);
      case '=': return n == '=' ? two(TokenKind::kEq) : one(TokenKind::kAssign);
      case '!':
        if (n == '=') return two(TokenKind::kNe);
        break;
      case '<': return n == '=' ? two(TokenKind::kLe) : one(TokenKind::kLt);
      case '>': return n == '=' ? two(TokenKind::kGe) : one(TokenKind::kGt);
      default: break;
    }
    Token t = Make(TokenKind::kBad, "");
    // One whole UTF-8 sequence, so that the message shows the character.
    std::size_t len = 1;
    while (i_ + len < text_.size() && (static_cast<unsigned char>(text_[i_ + len]) & 0xC0) == 0x80) {
      ++len;
    }
    t.text = std::string(text_.substr(i_, len));
    errors_->push_back({t.pos, "unexpected character '" + t.text + "'"});
    Advance(len);
    return t;
  }

  std::string_view text_;
  std::vector<LexError>* errors_;
  std::size_t i_ = 0;
  std::size_t line_start_ = 0;
  int line_ = 1;
};

}  // namespace

std::vector<Token> Lex(std::string_view text, std::vector<LexError>* errors) {
  return Lexer(text, errors).Run();
}

std::string Describe(const Token& t) {
  switch (t.kind) {
    case TokenKind::kNewline: return "end of line";
    case TokenKind::kEnd: return "end of input";
    default: return "'" + t.text + "'";
  }
}

}  // namespace rover::apl::sequencer::internal
