#include "rover/apl/sequencer/parser.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "lexer.hpp"
#include "rover/apl/sequencer/commands.hpp"
#include "rover/apl/sequencer/condition.hpp"
#include "rover/apl/sequencer/units.hpp"
#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/params.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::sequencer {
namespace {

using internal::Token;
using internal::TokenKind;

// Reserved words: they open, branch or close blocks, or separate the parts of a statement
// (MAX, UNTIL, TIMEOUT, AND, OR, NOT come right after a value). No TARGET or CONST may be named
// like one, in any case. The words that only ever start a statement of their own (TARGET,
// CONST, WAIT) and the command names are not reserved: a name is only read where a value
// goes, never at the start of a statement, so `TARGET target = (6, 0)` and `WAIT wait` are
// unambiguous.
const std::vector<std::string> kReserved = {"IF",  "ELSE",    "END",   "REPEAT", "WHILE", "MAX",
                                            "UNTIL", "TIMEOUT", "ON_ABORT", "AND", "OR", "NOT"};

constexpr int kMaxLoopCount = 10000;      // REPEAT n and WHILE ... MAX n
constexpr double kMaxWaitS = 86400.0;     // WAIT and TIMEOUT

std::string Upper(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return out;
}

std::string Lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

bool IsReserved(std::string_view word) {
  const std::string u = Upper(word);
  return std::find(kReserved.begin(), kReserved.end(), u) != kReserved.end();
}

std::string Quote(std::string_view s) { return "'" + std::string(s) + "'"; }

/// Where a block opened, for messages about its END and ELSE.
struct BlockContext {
  int depth = 0;             // 0 = top level
  std::string opener;        // "IF", "REPEAT", "WHILE", "ON_ABORT", "ELSE"
  SourcePos opener_pos;
  bool allows_else = false;  // an IF's then-branch
  bool in_else = false;      // an IF's else-branch (opener is "IF")
};

enum class BlockEnd { kEnd, kElse, kEof };

class Parser {
 public:
  Parser(std::string_view text, const ParseOptions& options) : text_(text), options_(options) {
    std::vector<internal::LexError> lex_errors;
    tokens_ = internal::Lex(text, &lex_errors);
    for (auto& e : lex_errors) Report(e.pos, std::move(e.message));
    std::size_t start = 0;
    for (std::size_t k = 0; k <= text.size(); ++k) {
      if (k == text.size() || text[k] == '\n') {
        lines_.push_back(text.substr(start, k - start));
        start = k + 1;
      }
    }
    seq_.source = options.source;
  }

  ParseReport Run() {
    const BlockEnd end = ParseStatements(&seq_.statements, BlockContext{});
    ROVER_DEMAND(end == BlockEnd::kEof);
    for (const auto& [name, value] : options_.overrides) {
      if (used_overrides_.count(name) == 0) {
        std::vector<std::string> defined;
        for (const auto& [n, _] : definitions_) defined.push_back(n);
        Error({}, "override " + Quote(name) + " names no TARGET or CONST of the sequence" +
                      DidYouMean(name, defined));
      }
    }
    if (seq_.statements.empty() && errors_.empty()) {
      Error({1, 1}, "the sequence has no statements to run");
    }
    ParseReport report;
    report.errors = std::move(errors_);
    if (report.errors.empty()) report.sequence = std::move(seq_);
    return report;
  }

 private:
  // ---- tokens ----------------------------------------------------------------------------------

  const Token& Peek(std::size_t ahead = 0) const {
    return tokens_[std::min(i_ + ahead, tokens_.size() - 1)];
  }
  const Token& Next() {
    const Token& t = tokens_[i_];
    if (i_ + 1 < tokens_.size()) ++i_;
    return t;
  }
  bool AtLineEnd() const {
    return Peek().kind == TokenKind::kNewline || Peek().kind == TokenKind::kEnd;
  }
  bool PeekWord(std::string_view upper_word, std::size_t ahead = 0) const {
    return Peek(ahead).kind == TokenKind::kIdent && Upper(Peek(ahead).text) == upper_word;
  }
  /// Skips to the start of the next line.
  void SkipLine() {
    while (!AtLineEnd()) Next();
    if (Peek().kind == TokenKind::kNewline) Next();
  }
  /// Consumes the end of the line; anything else before it is an error.
  bool ExpectLineEnd(std::string_view after) {
    if (!AtLineEnd()) {
      Error(Peek().pos, "unexpected " + internal::Describe(Peek()) + " after " +
                            std::string(after));
      SkipLine();
      return false;
    }
    if (Peek().kind == TokenKind::kNewline) Next();
    return true;
  }

  /// The source text from `from` to the end of its line, without comment and trailing blanks.
  std::string TextFrom(SourcePos from) const {
    if (from.line < 1 || from.line > static_cast<int>(lines_.size())) return "";
    std::string_view l = lines_[from.line - 1];
    l = l.substr(std::min(l.size(), static_cast<std::size_t>(from.column - 1)));
    l = l.substr(0, std::min(l.size(), l.find('#')));
    while (!l.empty() && std::isspace(static_cast<unsigned char>(l.back()))) l.remove_suffix(1);
    return std::string(l);
  }
  /// The source text from `from` up to (not including) the token at `to`.
  std::string TextBetween(SourcePos from, const Token& to) const {
    std::string all = TextFrom(from);
    if (to.pos.line == from.line && to.kind != TokenKind::kNewline &&
        to.kind != TokenKind::kEnd) {
      all = all.substr(0, static_cast<std::size_t>(std::max(0, to.pos.column - from.column)));
    }
    while (!all.empty() && std::isspace(static_cast<unsigned char>(all.back()))) all.pop_back();
    return all;
  }

  /// Records an error; returns false (for `return Error(...)` in checks).
  bool Report(SourcePos pos, std::string message) {
    ++error_count_;
    if (static_cast<int>(errors_.size()) < options_.max_errors) {
      errors_.push_back({pos, std::move(message)});
    }
    return false;
  }
  /// A parse error. One about a character the language does not use (a kBad token, which the
  /// lexer has reported already) is counted but not reported a second time.
  bool Error(SourcePos pos, std::string message) {
    if (Peek().kind == TokenKind::kBad && Peek().pos == pos) {
      ++error_count_;
      return false;
    }
    return Report(pos, std::move(message));
  }
  /// True (the error counted, not reported) when `name` is a TARGET or CONST whose definition
  /// had an error: its uses fail without repeating it.
  bool DefinitionFailed(const std::string& name) {
    if (broken_definitions_.count(name) == 0) return false;
    ++error_count_;
    return true;
  }

  // ---- blocks --------------------------------------------------------------------------------

  BlockEnd ParseStatements(std::vector<Statement>* out, const BlockContext& ctx) {
    while (true) {
      while (Peek().kind == TokenKind::kNewline) Next();
      const Token& t = Peek();
      if (t.kind == TokenKind::kEnd) return BlockEnd::kEof;
      if (t.kind != TokenKind::kIdent) {
        Error(t.pos, "expected a statement, got " + internal::Describe(t));
        SkipLine();
        continue;
      }
      const std::string word = Upper(t.text);
      if (word == "END") {
        const SourcePos pos = Next().pos;
        // A line is reported for its first error only: "END x" is a syntax error on its own, and
        // inside a block it still closes the block.
        const bool clean = ExpectLineEnd("END");
        if (ctx.depth == 0) {
          if (clean) Error(pos, "END without an open block");
          continue;
        }
        return BlockEnd::kEnd;
      }
      if (word == "ELSE") {
        if (ctx.allows_else) {
          Next();
          return BlockEnd::kElse;
        }
        if (ctx.in_else) {
          Error(t.pos, "a second ELSE for the IF at line " + std::to_string(ctx.opener_pos.line));
        } else if (ctx.depth > 0) {
          Error(t.pos, "ELSE without IF (inside the " + ctx.opener + " at line " +
                           std::to_string(ctx.opener_pos.line) + ")");
        } else {
          Error(t.pos, "ELSE without IF");
        }
        SkipLine();
        continue;
      }
      if (std::optional<Statement> s = ParseStatement(ctx)) out->push_back(std::move(*s));
    }
  }

  /// Parses a block body that must end with END; reports a missing one at the opener.
  void ParseBody(std::vector<Statement>* out, const BlockContext& ctx) {
    if (ParseStatements(out, ctx) == BlockEnd::kEof) {
      Error(ctx.opener_pos, ctx.opener + " at line " + std::to_string(ctx.opener_pos.line) +
                                " has no END");
    }
  }

  BlockContext Child(const BlockContext& parent, std::string opener, SourcePos pos,
                     bool allows_else = false, bool in_else = false) const {
    return BlockContext{parent.depth + 1, std::move(opener), pos, allows_else, in_else};
  }

  std::optional<Statement> ParseStatement(const BlockContext& ctx) {
    const Token& t = Peek();
    const std::string word = Upper(t.text);
    if (word == "TARGET" || word == "CONST") {
      if (ctx.depth > 0) {
        Error(t.pos, word + " definitions belong at the top level, outside blocks");
        SkipLine();
        return std::nullopt;
      }
      if (word == "TARGET") {
        ParseTargetDefinition();
      } else {
        ParseConstDefinition();
      }
      return std::nullopt;
    }
    if (word == "ON_ABORT") {
      ParseOnAbort(ctx);
      return std::nullopt;
    }
    if (word == "IF") {
      const SourcePos pos = Next().pos;
      return ParseIf(ctx, pos);
    }
    if (word == "REPEAT") return ParseRepeat(ctx);
    if (word == "WHILE") return ParseWhile(ctx);
    if (word == "WAIT") return ParseWait();
    if (word == "MAX" || word == "UNTIL" || word == "TIMEOUT" || word == "AND" || word == "OR" ||
        word == "NOT") {
      Error(t.pos, word + " cannot start a statement");
      SkipLine();
      return std::nullopt;
    }
    return ParseCommand();
  }

  void ParseOnAbort(const BlockContext& ctx) {
    const SourcePos pos = Next().pos;
    bool ok = ExpectLineEnd("ON_ABORT");
    if (ctx.depth > 0) {
      ok = Error(pos, "ON_ABORT belongs at the top level, outside blocks");
    } else if (abort_line_ > 0) {
      ok = Error(pos, "a second ON_ABORT block (the first is at line " +
                          std::to_string(abort_line_) + ")");
    }
    std::vector<Statement> body;
    const int errors_before = error_count_;
    ParseBody(&body, Child(ctx, "ON_ABORT", pos));
    if (ok && error_count_ == errors_before) {
      abort_line_ = pos.line;
      seq_.on_abort = std::move(body);
    } else if (abort_line_ == 0 && ctx.depth == 0) {
      abort_line_ = pos.line;
    }
  }

  // `if_pos` is where the IF (or ELSE IF) keyword was; the condition starts at Peek().
  std::optional<Statement> ParseIf(const BlockContext& ctx, SourcePos if_pos) {
    Statement s;
    s.kind = Statement::Kind::kIf;
    s.pos = if_pos;
    s.text = TextFrom(if_pos);
    std::optional<Condition> cond = ParseConditionLine("IF");
    const BlockContext then_ctx = Child(ctx, "IF", if_pos, /*allows_else=*/true);
    const BlockEnd end = ParseStatements(&s.body, then_ctx);
    if (end == BlockEnd::kEof) {
      Error(if_pos, "IF at line " + std::to_string(if_pos.line) + " has no END");
      return std::nullopt;
    }
    if (end == BlockEnd::kElse) {
      if (PeekWord("IF")) {
        // ELSE IF: an IF alone in the else-branch that shares this IF's END.
        const SourcePos nested = Next().pos;
        std::optional<Statement> inner = ParseIf(ctx, nested);
        if (!inner) return std::nullopt;
        s.else_body.push_back(std::move(*inner));
      } else {
        ExpectLineEnd("ELSE");
        ParseBody(&s.else_body, Child(ctx, "IF", if_pos, false, /*in_else=*/true));
      }
    }
    if (!cond) return std::nullopt;
    s.condition = std::move(*cond);
    return s;
  }

  std::optional<Statement> ParseRepeat(const BlockContext& ctx) {
    Statement s;
    s.kind = Statement::Kind::kRepeat;
    s.pos = Next().pos;
    s.text = TextFrom(s.pos);
    bool ok = true;
    if (AtLineEnd()) {
      ok = Error(s.pos, "unbounded loop: REPEAT needs a count (REPEAT n)");
      ExpectLineEnd("REPEAT");
    } else if (std::optional<int> n = ParseCount("REPEAT count")) {
      s.count = *n;
      ok = ExpectLineEnd("the REPEAT count");
    } else {
      ok = false;
      SkipLine();
    }
    ParseBody(&s.body, Child(ctx, "REPEAT", s.pos));
    if (!ok) return std::nullopt;
    return s;
  }

  std::optional<Statement> ParseWhile(const BlockContext& ctx) {
    Statement s;
    s.kind = Statement::Kind::kWhile;
    s.pos = Next().pos;
    s.text = TextFrom(s.pos);
    bool ok = true;
    std::optional<Condition> cond = ParseCondition();
    if (!cond) {
      ok = false;
      SkipLine();
    } else if (!PeekWord("MAX")) {
      ok = Error(s.pos, "unbounded loop: WHILE needs MAX n (the most times the body runs)");
      SkipLine();
    } else {
      Next();
      if (std::optional<int> n = ParseCount("MAX")) {
        s.count = *n;
        ok = ExpectLineEnd("the MAX count");
      } else {
        ok = false;
        SkipLine();
      }
    }
    ParseBody(&s.body, Child(ctx, "WHILE", s.pos));
    if (!ok) return std::nullopt;
    s.condition = std::move(*cond);
    return s;
  }

  std::optional<Statement> ParseWait() {
    Statement s;
    s.pos = Next().pos;
    s.text = TextFrom(s.pos);
    if (PeekWord("UNTIL")) {
      Next();
      s.kind = Statement::Kind::kWaitUntil;
      std::optional<Condition> cond = ParseCondition();
      if (!cond) {
        SkipLine();
        return std::nullopt;
      }
      if (!PeekWord("TIMEOUT")) {
        Error(AtLineEnd() ? s.pos : Peek().pos,
              "unbounded wait: WAIT UNTIL needs TIMEOUT <duration>");
        SkipLine();
        return std::nullopt;
      }
      Next();
      std::optional<double> d = ParseDuration("TIMEOUT", Bounds::OpenLow(0.0, kMaxWaitS));
      if (!d || !ExpectLineEnd("the TIMEOUT")) {
        if (!d) SkipLine();
        return std::nullopt;
      }
      s.condition = std::move(*cond);
      s.seconds = *d;
    } else {
      s.kind = Statement::Kind::kWait;
      if (AtLineEnd()) {
        Error(s.pos, "WAIT needs a duration (WAIT 5 s) or UNTIL <condition> TIMEOUT <duration>");
        SkipLine();
        return std::nullopt;
      }
      std::optional<double> d = ParseDuration("WAIT", Bounds::Closed(0.0, kMaxWaitS));
      if (!d || !ExpectLineEnd("the WAIT duration")) {
        if (!d) SkipLine();
        return std::nullopt;
      }
      s.seconds = *d;
    }
    s.step = NewStep(s.pos, s.text);
    return s;
  }

  int NewStep(SourcePos pos, const std::string& text) {
    seq_.steps.push_back({pos.line, text});
    return static_cast<int>(seq_.steps.size());
  }

  // ---- definitions -----------------------------------------------------------------------------

  /// The defined name after TARGET or CONST and the '='; nullopt (line skipped) on error.
  std::optional<std::string> DefinitionName(const std::string& keyword) {
    if (Peek().kind != TokenKind::kIdent) {
      Error(Peek().pos, keyword + " needs a name, got " + internal::Describe(Peek()));
      SkipLine();
      return std::nullopt;
    }
    const Token& name = Next();
    std::string problem;
    if (name.text.find('.') != std::string::npos || name.text.find('/') != std::string::npos) {
      problem = "may not contain '.' or '/'";
    } else if (IsReserved(name.text)) {
      problem = "is a reserved word";
    } else if (FindQuantity(name.text)) {
      problem = "is the name of a quantity";
    } else if (auto it = definitions_.find(name.text); it != definitions_.end()) {
      problem = "is already defined at line " + std::to_string(it->second);
    }
    if (!problem.empty()) {
      Error(name.pos, keyword + " name " + Quote(name.text) + " " + problem);
      SkipLine();
      return std::nullopt;
    }
    if (Peek().kind != TokenKind::kAssign) {
      Error(Peek().pos, "expected '=' after " + keyword + " " + name.text + ", got " +
                            internal::Describe(Peek()));
      SkipLine();
      return std::nullopt;
    }
    Next();
    definitions_[name.text] = name.pos.line;
    return name.text;
  }

  /// Runs `parse` on the override of `name` if there is one (errors are reported at `at` and
  /// name the override), else on the text. Returns its result.
  template <class F>
  auto WithOverride(const std::string& name, SourcePos at, F parse) -> decltype(parse()) {
    auto it = options_.overrides.find(name);
    if (it == options_.overrides.end()) return parse();
    used_overrides_.insert(name);
    SkipLine();  // the text's own value is replaced
    std::vector<internal::LexError> lex_errors;
    std::vector<Token> saved = std::move(tokens_);
    const std::size_t saved_i = i_;
    tokens_ = internal::Lex(it->second, &lex_errors);
    i_ = 0;
    const std::size_t first_error = errors_.size();
    for (auto& e : lex_errors) Report(e.pos, std::move(e.message));
    auto result = parse();
    if (!AtLineEnd()) {
      Error(Peek().pos, "unexpected " + internal::Describe(Peek()) + " after the value");
      result = decltype(result){};
    }
    for (std::size_t k = first_error; k < errors_.size(); ++k) {
      errors_[k].message = "override " + name + "=" + it->second + ": " + errors_[k].message;
      errors_[k].pos = at;
    }
    if (lex_errors.size() > 0) result = decltype(result){};
    tokens_ = std::move(saved);
    i_ = saved_i;
    return result;
  }

  void ParseTargetDefinition() {
    const SourcePos pos = Next().pos;
    std::optional<std::string> name = DefinitionName("TARGET");
    if (!name) return;
    std::optional<std::vector<double>> p = WithOverride(*name, pos, [&] {
      return ParseTuple(*name, 2, 3, "m", Bounds::Closed(-1e4, 1e4), "(x, y) or (x, y, z)");
    });
    if (!p) {
      broken_definitions_.insert(*name);
      if (options_.overrides.count(*name) == 0) SkipLine();
      return;
    }
    if (options_.overrides.count(*name) == 0 && !ExpectLineEnd("the TARGET point")) {
      broken_definitions_.insert(*name);
      return;
    }
    seq_.targets[*name] = Vec3{(*p)[0], (*p)[1], p->size() > 2 ? (*p)[2] : 0.0};
  }

  void ParseConstDefinition() {
    const SourcePos pos = Next().pos;
    std::optional<std::string> name = DefinitionName("CONST");
    if (!name) return;
    std::optional<Constant> c = WithOverride(*name, pos, [&] { return ParseConstantValue(*name); });
    if (!c) {
      broken_definitions_.insert(*name);
      if (options_.overrides.count(*name) == 0) SkipLine();
      return;
    }
    if (options_.overrides.count(*name) == 0 && !ExpectLineEnd("the CONST value")) {
      broken_definitions_.insert(*name);
      return;
    }
    seq_.constants[*name] = *c;
  }

  std::optional<Constant> ParseConstantValue(const std::string& name) {
    const Token& t = Peek();
    if (t.kind == TokenKind::kIdent) {
      if (auto it = seq_.constants.find(t.text); it != seq_.constants.end()) {
        Next();
        return it->second;
      }
    }
    if (t.kind != TokenKind::kNumber) {
      Error(t.pos, "CONST " + name + " needs a number (with an optional unit), got " +
                       internal::Describe(t));
      return std::nullopt;
    }
    Next();
    Constant c{t.number, ""};
    if (!CheckNumber(name, t)) return std::nullopt;
    if (UnitFollows()) {
      const Token& u = Next();
      if (FindUnit(u.text) == nullptr) {
        Error(u.pos, "unknown unit " + Quote(u.text) + DidYouMean(u.text, UnitNames()));
        return std::nullopt;
      }
      c.unit = u.text;
    }
    return c;
  }

  // ---- values ----------------------------------------------------------------------------------

  /// True when the next token is a unit written after a number: an identifier that is no
  /// keyword and does not start the next `name=value`.
  bool UnitFollows() const {
    return Peek().kind == TokenKind::kIdent && !IsReserved(Peek().text) &&
           Peek(1).kind != TokenKind::kAssign;
  }

  bool CheckNumber(std::string_view what, const Token& t) {
    if (!std::isfinite(t.number)) {
      return Error(t.pos, std::string(what) + " = " + t.text + " is not a finite number");
    }
    return true;
  }

  /// A number with an optional unit, or a CONST, expressed in `unit`. `what` names the
  /// consumer in messages.
  std::optional<double> ParseScalar(const std::string& what, std::string_view unit) {
    const Unit& to = DeclaredUnit(unit);
    const Token& t = Peek();
    if (t.kind == TokenKind::kNumber) {
      Next();
      if (!CheckNumber(what, t)) return std::nullopt;
      if (!UnitFollows()) return t.number;
      const Token& u = Next();
      const Unit* from = FindUnit(u.text);
      if (from == nullptr) {
        Error(u.pos, "unknown unit " + Quote(u.text) + DidYouMean(u.text, UnitNames()));
        return std::nullopt;
      }
      Result<double> v = ConvertUnit(t.number, *from, to, what);
      if (!v.ok()) {
        Error(u.pos, v.status().message());
        return std::nullopt;
      }
      return *v;
    }
    if (t.kind == TokenKind::kIdent && !IsReserved(t.text)) {
      Next();
      auto it = seq_.constants.find(t.text);
      if (it == seq_.constants.end()) {
        if (DefinitionFailed(t.text)) return std::nullopt;
        if (seq_.targets.count(t.text) > 0) {
          Error(t.pos, Quote(t.text) + " is a TARGET (a point); " + what + " takes a number");
        } else {
          std::vector<std::string> known;
          for (const auto& [n, _] : seq_.constants) known.push_back(n);
          Error(t.pos, "unknown constant " + Quote(t.text) + DidYouMean(t.text, known));
        }
        return std::nullopt;
      }
      if (it->second.unit.empty()) return it->second.value;
      Result<double> v = ConvertUnit(it->second.value, *FindUnit(it->second.unit), to, what);
      if (!v.ok()) {
        Error(t.pos, "constant " + t.text + ": " + v.status().message());
        return std::nullopt;
      }
      return *v;
    }
    Error(t.pos, what + " expects a number, got " + internal::Describe(t));
    return std::nullopt;
  }

  /// ParseScalar, then the range check. A value out of range is reported at `range_at` (the
  /// argument's name=, which the message names) when given, else at the value.
  std::optional<double> ParseChecked(const std::string& what, std::string_view unit,
                                     const Bounds& bounds,
                                     std::optional<SourcePos> range_at = std::nullopt) {
    const SourcePos pos = range_at.value_or(Peek().pos);
    std::optional<double> v = ParseScalar(what, unit);
    if (!v) return std::nullopt;
    const Status s = CheckRange(what, *v, bounds, unit);
    if (!s.ok()) {
      Error(pos, s.message());
      return std::nullopt;
    }
    return v;
  }

  std::optional<double> ParseDuration(const std::string& what, const Bounds& bounds) {
    return ParseChecked(what, "s", bounds);
  }

  std::optional<int> ParseCount(const std::string& what) {
    const SourcePos pos = Peek().pos;
    std::optional<double> v = ParseScalar(what, "");
    if (!v) return std::nullopt;
    if (*v != std::floor(*v)) {
      Error(pos, what + " = " + FormatNumber(*v) + " is not a whole number");
      return std::nullopt;
    }
    const Status s = CheckIntRange(what, static_cast<long long>(*v), 1, kMaxLoopCount);
    if (!s.ok()) {
      Error(pos, s.message());
      return std::nullopt;
    }
    return static_cast<int>(*v);
  }

  /// "(a, b, ...)" with between `min_n` and `max_n` numbers, each in `unit` and `bounds`
  /// (`range_at` as in ParseChecked).
  std::optional<std::vector<double>> ParseTuple(const std::string& what, int min_n, int max_n,
                                                std::string_view unit, const Bounds& bounds,
                                                std::string_view shape,
                                                std::optional<SourcePos> range_at = std::nullopt) {
    const Token& open = Peek();
    if (open.kind != TokenKind::kLParen) {
      Error(open.pos, what + " expects " + std::string(shape) + ", got " +
                          internal::Describe(open));
      return std::nullopt;
    }
    Next();
    std::vector<double> out;
    while (true) {
      const std::string element = what + "[" + std::to_string(out.size()) + "]";
      std::optional<double> v = ParseChecked(element, unit, bounds, range_at);
      if (!v) return std::nullopt;
      out.push_back(*v);
      if (Peek().kind == TokenKind::kComma) {
        Next();
        continue;
      }
      if (Peek().kind == TokenKind::kRParen) {
        Next();
        break;
      }
      Error(Peek().pos, "expected ',' or ')' in " + what + ", got " + internal::Describe(Peek()));
      return std::nullopt;
    }
    const int n = static_cast<int>(out.size());
    if (n < min_n || n > max_n) {
      const std::string count = min_n == max_n ? std::to_string(min_n)
                                               : std::to_string(min_n) + " or " +
                                                     std::to_string(max_n);
      Error(open.pos, what + " expects " + count + " numbers " + std::string(shape) + ", got " +
                          std::to_string(n));
      return std::nullopt;
    }
    return out;
  }

  /// A point literal or a TARGET name (`range_at` as in ParseChecked).
  std::optional<ArgValue> ParsePoint(const std::string& what, int min_n, int max_n,
                                     std::string_view shape,
                                     std::optional<SourcePos> range_at = std::nullopt) {
    ArgValue v;
    v.pos = Peek().pos;
    const Token& t = Peek();
    if (t.kind == TokenKind::kIdent) {
      Next();
      auto it = seq_.targets.find(t.text);
      if (it == seq_.targets.end()) {
        if (DefinitionFailed(t.text)) return std::nullopt;
        if (seq_.constants.count(t.text) > 0) {
          Error(t.pos, Quote(t.text) + " is a CONST (a number); " + what +
                           " takes a point or a TARGET name");
        } else {
          std::vector<std::string> known;
          for (const auto& [n, _] : seq_.targets) known.push_back(n);
          Error(t.pos, "unknown target " + Quote(t.text) + DidYouMean(t.text, known));
        }
        return std::nullopt;
      }
      v.name = t.text;
      v.numbers = {it->second.x, it->second.y, it->second.z};
      v.numbers.resize(static_cast<std::size_t>(max_n));
      return v;
    }
    std::optional<std::vector<double>> p =
        ParseTuple(what, min_n, max_n, "m", Bounds::Closed(-1e4, 1e4), shape, range_at);
    if (!p) return std::nullopt;
    v.numbers = std::move(*p);
    return v;
  }

  /// The value of argument `a`, written at `at` (its name=, or the value itself when positional):
  /// shape and unit errors are reported where they are, range errors at `at`.
  std::optional<ArgValue> ParseArgValue(const ArgSpec& a, SourcePos at) {
    const std::string what(a.name);
    ArgValue v;
    v.type = a.type;
    v.given = true;
    v.pos = at;
    switch (a.type) {
      case ArgType::kNumber:
      case ArgType::kInteger: {
        if (Peek().kind == TokenKind::kIdent) v.name = Peek().text;
        std::optional<double> n = ParseChecked(what, a.unit, a.bounds, at);
        if (!n) return std::nullopt;
        if (a.type == ArgType::kInteger && *n != std::floor(*n)) {
          Error(at, what + " = " + FormatNumber(*n) + " is not a whole number");
          return std::nullopt;
        }
        v.number = *n;
        return v;
      }
      case ArgType::kPoint2:
      case ArgType::kPoint3: {
        const bool three = a.type == ArgType::kPoint3;
        std::optional<ArgValue> p =
            ParsePoint(what, three ? 3 : 2, three ? 3 : 2, three ? "(x, y, z)" : "(x, y)", at);
        if (!p) return std::nullopt;
        p->type = a.type;
        p->given = true;
        p->pos = at;
        return p;
      }
      case ArgType::kPixel:
      case ArgType::kTuple: {
        const int n = a.type == ArgType::kPixel ? 2 : a.size;
        const std::string shape = a.type == ArgType::kPixel ? "(u, v)" : "(a, b, ...)";
        std::optional<std::vector<double>> t =
            ParseTuple(what, n, n, a.unit, a.bounds, shape, at);
        if (!t) return std::nullopt;
        v.numbers = std::move(*t);
        return v;
      }
      case ArgType::kWord: {
        const Token& t = Peek();
        std::vector<std::string> choices(a.choices.begin(), a.choices.end());
        std::string all;
        for (const auto& c : choices) all += (all.empty() ? "" : ", ") + c;
        if (t.kind != TokenKind::kIdent) {
          Error(t.pos, what + " must be one of " + all + ", got " + internal::Describe(t));
          return std::nullopt;
        }
        Next();
        const std::string w = Upper(t.text);
        if (std::find(choices.begin(), choices.end(), w) == choices.end()) {
          Error(t.pos, what + " must be one of " + all + ", got " + Quote(t.text) +
                           DidYouMean(w, choices));
          return std::nullopt;
        }
        v.word = w;
        return v;
      }
    }
    ROVER_UNREACHABLE();
  }

  // ---- commands --------------------------------------------------------------------------------

  /// Words that may belong to a command name: identifiers not followed by '='.
  std::vector<std::string> CandidateWords() const {
    std::vector<std::string> words;
    for (int k = 0; k < MaxCommandWords(); ++k) {
      const Token& t = Peek(static_cast<std::size_t>(k));
      if (t.kind != TokenKind::kIdent || Peek(static_cast<std::size_t>(k) + 1).kind ==
                                             TokenKind::kAssign) {
        break;
      }
      words.push_back(Upper(t.text));
    }
    return words;
  }

  /// Reports the unknown command that starts at `first`; `words` are CandidateWords().
  ///
  /// What is quoted is what the hint was matched on: the longest run of leading words (two or
  /// more) that is close to a command name of as many words ("DRIV ARC" -> DRIVE ARC, "DRIVE
  /// ARK" -> DRIVE ARC); else, when the first word starts command names, the list of those; else
  /// the first word alone, with a hint among names, first words and statement keywords.
  void UnknownCommand(const Token& first, const std::vector<std::string>& words) {
    const std::vector<std::string> names = CommandNames();
    auto word_count = [](const std::string& n) {
      return 1 + static_cast<std::size_t>(std::count(n.begin(), n.end(), ' '));
    };
    for (std::size_t n = words.size(); n >= 2; --n) {
      std::vector<std::string> same_length;
      for (const auto& name : names) {
        if (word_count(name) == n) same_length.push_back(name);
      }
      std::string joined;
      std::string as_written;
      for (std::size_t k = 0; k < n; ++k) {
        joined += (k ? " " : "") + words[k];
        as_written += (k ? " " : "") + Peek(k).text;
      }
      const std::string hint = DidYouMean(joined, same_length);
      if (!hint.empty()) {
        Error(first.pos, "unknown command " + Quote(as_written) + hint);
        return;
      }
    }
    std::vector<std::string> with_prefix;
    for (const auto& n : names) {
      if (n.rfind(words[0] + " ", 0) == 0) with_prefix.push_back(n);
    }
    if (!with_prefix.empty()) {
      std::string list;
      for (const auto& n : with_prefix) list += (list.empty() ? "" : ", ") + n;
      Error(first.pos, words[0] + " needs one of: " + list);
      return;
    }
    std::vector<std::string> known = names;
    for (const auto& n : names) known.push_back(n.substr(0, n.find(' ')));
    for (const char* k : {"TARGET", "CONST", "IF", "REPEAT", "WHILE", "WAIT", "ON_ABORT"}) {
      known.emplace_back(k);
    }
    std::sort(known.begin(), known.end());
    known.erase(std::unique(known.begin(), known.end()), known.end());
    Error(first.pos, "unknown command " + Quote(first.text) + DidYouMean(words[0], known));
  }

  std::optional<Statement> ParseCommand() {
    const Token first = Peek();
    const std::vector<std::string> words = CandidateWords();
    const CommandSpec* spec = nullptr;
    std::size_t used = 0;
    for (std::size_t n = words.size(); n >= 1 && spec == nullptr; --n) {
      std::string name;
      for (std::size_t k = 0; k < n; ++k) name += (k ? " " : "") + words[k];
      spec = FindCommand(name);
      if (spec != nullptr) used = n;
    }
    if (spec == nullptr) {
      if (words.empty()) {
        Error(first.pos, "expected a command, got " + Quote(first.text) + "=");
      } else {
        UnknownCommand(first, words);
      }
      SkipLine();
      return std::nullopt;
    }
    for (std::size_t k = 0; k < used; ++k) Next();

    Statement s;
    s.kind = Statement::Kind::kCommand;
    s.pos = first.pos;
    s.text = TextFrom(first.pos);
    CommandCall& call = s.command;
    call.kind = spec->kind;
    call.pos = first.pos;
    call.text = s.text;
    const std::string cmd(spec->name);

    bool first_arg = true;
    while (!AtLineEnd()) {
      const Token& t = Peek();
      const ArgSpec* a = nullptr;
      if (t.kind == TokenKind::kIdent && Peek(1).kind == TokenKind::kAssign) {
        const std::string name = Lower(t.text);
        a = spec->FindArg(name);
        if (a == nullptr) {
          Error(t.pos, cmd + " has no argument " + Quote(t.text) +
                           DidYouMean(name, spec->ArgNames()));
          SkipLine();
          return std::nullopt;
        }
        Next();
        Next();
      } else if (first_arg && !spec->positional.empty()) {
        a = spec->FindArg(spec->positional);
      } else {
        std::string names;
        for (const auto& n : spec->ArgNames()) names += (names.empty() ? "" : ", ") + n + "=";
        Error(t.pos, spec->args.size() == 1
                         ? cmd + " takes no arguments but " + std::string(kOnFaultArg) +
                               "=, got " + internal::Describe(t)
                         : "expected an argument name=value of " + cmd + " (" + names +
                               "), got " + internal::Describe(t));
        SkipLine();
        return std::nullopt;
      }
      first_arg = false;
      const std::string arg_name(a->name);
      if (auto it = call.args.find(arg_name); it != call.args.end()) {
        Error(t.pos, cmd + ": argument " + Quote(arg_name) + " given twice (first at column " +
                         std::to_string(it->second.pos.column) + ")");
        SkipLine();
        return std::nullopt;
      }
      std::optional<ArgValue> v = ParseArgValue(*a, t.pos);
      if (!v) {
        SkipLine();
        return std::nullopt;
      }
      call.args[arg_name] = std::move(*v);
    }
    if (!ExpectLineEnd(cmd) || !CheckArguments(*spec, &call)) return std::nullopt;
    call.continue_on_goal_error = call.Get(std::string(kOnFaultArg)).word == "CONTINUE";
    s.step = NewStep(s.pos, s.text);
    return s;
  }

  /// Required, one-of and needs rules; fills defaults.
  bool CheckArguments(const CommandSpec& spec, CommandCall* call) {
    const std::string cmd(spec.name);
    for (const ArgSpec& a : spec.args) {
      if (a.required && !call->Has(std::string(a.name))) {
        std::string unit = a.unit.empty() || a.type == ArgType::kPoint2 ||
                                   a.type == ArgType::kPoint3
                               ? std::string(ArgTypeName(a.type))
                               : std::string(a.unit);
        return Error(call->pos,
                     cmd + " needs argument " + Quote(a.name) + " (" + unit + ")");
      }
    }
    std::set<std::string_view> groups;
    for (const ArgSpec& a : spec.args) {
      if (!a.one_of.empty()) groups.insert(a.one_of);
    }
    for (std::string_view g : groups) {
      std::vector<std::string> members;
      int given = 0;
      for (const ArgSpec& a : spec.args) {
        if (a.one_of != g) continue;
        members.push_back(Quote(a.name));
        if (call->Has(std::string(a.name))) ++given;
      }
      std::string list;
      for (const auto& m : members) list += (list.empty() ? "" : ", ") + m;
      if (given != 1) {
        return Error(call->pos, cmd + (given == 0 ? " needs" : " takes only") +
                                    " one of " + list + (given > 1 ? " (several given)" : ""));
      }
    }
    for (const ArgSpec& a : spec.args) {
      if (!a.needs.empty() && call->Has(std::string(a.name)) &&
          !call->Has(std::string(a.needs))) {
        return Error(call->Get(std::string(a.name)).pos,
                     cmd + ": argument " + Quote(a.name) + " needs argument " + Quote(a.needs));
      }
    }
    for (const ArgSpec& a : spec.args) {
      const std::string name(a.name);
      if (call->Has(name) || a.required || !a.one_of.empty()) continue;
      if (a.type == ArgType::kNumber || a.type == ArgType::kInteger) {
        if (!a.needs.empty()) continue;  // comes with its partner or not at all
        ArgValue v;
        v.type = a.type;
        v.number = a.default_value;
        v.pos = call->pos;
        call->args[name] = v;
      } else if (a.type == ArgType::kWord) {
        ArgValue v;
        v.type = a.type;
        v.word = std::string(a.default_word);
        v.pos = call->pos;
        call->args[name] = v;
      }
    }
    return true;
  }

  // ---- conditions ------------------------------------------------------------------------------

  /// A condition that must end its line (IF); on error the line is skipped.
  std::optional<Condition> ParseConditionLine(const std::string& keyword) {
    std::optional<Condition> c = ParseCondition();
    if (!c) {
      SkipLine();
      return std::nullopt;
    }
    if (!ExpectLineEnd("the " + keyword + " condition")) return std::nullopt;
    return c;
  }

  std::optional<Condition> ParseCondition() {
    if (AtLineEnd()) {
      Error(Peek().pos, "expected a condition, got end of line");
      return std::nullopt;
    }
    return ParseBinary(/*is_or=*/true);
  }

  std::optional<Condition> ParseBinary(bool is_or) {
    const SourcePos start = Peek().pos;
    std::optional<Condition> first = is_or ? ParseBinary(false) : ParseNot();
    if (!first) return std::nullopt;
    const std::string op = is_or ? "OR" : "AND";
    if (!PeekWord(op)) return first;
    Condition c;
    c.op = is_or ? Condition::Op::kOr : Condition::Op::kAnd;
    c.pos = start;
    c.operands.push_back(std::move(*first));
    while (PeekWord(op)) {
      Next();
      std::optional<Condition> next = is_or ? ParseBinary(false) : ParseNot();
      if (!next) return std::nullopt;
      c.operands.push_back(std::move(*next));
    }
    c.text = TextBetween(start, Peek());
    return c;
  }

  std::optional<Condition> ParseNot() {
    const Token& t = Peek();
    if (PeekWord("NOT")) {
      Next();
      std::optional<Condition> inner = ParseNot();
      if (!inner) return std::nullopt;
      Condition c;
      c.op = Condition::Op::kNot;
      c.pos = t.pos;
      c.operands.push_back(std::move(*inner));
      c.text = TextBetween(t.pos, Peek());
      return c;
    }
    if (t.kind == TokenKind::kLParen) {
      const SourcePos open = Next().pos;
      std::optional<Condition> inner = ParseBinary(true);
      if (!inner) return std::nullopt;
      if (Peek().kind != TokenKind::kRParen) {
        Error(Peek().pos, "expected ')' to close the '(' at column " +
                              std::to_string(open.column) + ", got " + internal::Describe(Peek()));
        return std::nullopt;
      }
      Next();
      return inner;
    }
    return ParseComparison();
  }

  std::optional<Condition> ParseComparison() {
    const Token q = Peek();
    if (q.kind != TokenKind::kIdent) {
      Error(q.pos, "expected a quantity (" + JoinQuantities() + "), got " + internal::Describe(q));
      return std::nullopt;
    }
    std::optional<Quantity> quantity = FindQuantity(q.text);
    if (!quantity) {
      Error(q.pos, "unknown quantity " + Quote(q.text) + DidYouMean(Lower(q.text),
                                                                     QuantityNames()));
      return std::nullopt;
    }
    Next();
    Condition c;
    c.op = Condition::Op::kCompare;
    c.pos = q.pos;
    Comparison& cmp = c.compare;
    cmp.quantity = *quantity;
    const std::string qname = QuantityName(*quantity);
    if (*quantity == Quantity::kDistanceTo) {
      if (Peek().kind != TokenKind::kLParen) {
        Error(Peek().pos, "distance_to needs a target: distance_to(name) or distance_to((x, y))");
        return std::nullopt;
      }
      Next();
      std::optional<ArgValue> p = ParsePoint("distance_to", 2, 3, "(x, y) or (x, y, z)");
      if (!p) return std::nullopt;
      if (Peek().kind != TokenKind::kRParen) {
        Error(Peek().pos, "expected ')' after the distance_to target, got " +
                              internal::Describe(Peek()));
        return std::nullopt;
      }
      Next();
      cmp.point = {p->numbers[0], p->numbers[1], p->numbers.size() > 2 ? p->numbers[2] : 0.0};
      cmp.name = p->name;
    }
    const Token& rel = Peek();
    switch (rel.kind) {
      case TokenKind::kEq: cmp.relation = Relation::kEq; break;
      case TokenKind::kNe: cmp.relation = Relation::kNe; break;
      case TokenKind::kLt: cmp.relation = Relation::kLt; break;
      case TokenKind::kLe: cmp.relation = Relation::kLe; break;
      case TokenKind::kGt: cmp.relation = Relation::kGt; break;
      case TokenKind::kGe: cmp.relation = Relation::kGe; break;
      case TokenKind::kAssign:
        Error(rel.pos, "use '==' to compare, not '='");
        return std::nullopt;
      default:
        Error(rel.pos, "expected a comparison (==, !=, <, <=, >, >=) after " + qname + ", got " +
                           internal::Describe(rel));
        return std::nullopt;
    }
    Next();
    if (IsEnumerated(*quantity)) {
      if (cmp.relation != Relation::kEq && cmp.relation != Relation::kNe) {
        Error(rel.pos, qname + " can only be compared with == or !=");
        return std::nullopt;
      }
      const Token& v = Peek();
      const auto& names = QuantityValueNames(*quantity);
      std::string all;
      for (const auto& n : names) all += (all.empty() ? "" : ", ") + n;
      if (v.kind != TokenKind::kIdent) {
        Error(v.pos, qname + " is one of " + all + "; got " + internal::Describe(v));
        return std::nullopt;
      }
      Next();
      const std::string w = Upper(v.text);
      auto it = std::find(names.begin(), names.end(), w);
      if (it == names.end()) {
        std::string hint = DidYouMean(w, names);
        Error(v.pos, "unknown value " + Quote(v.text) + " for " + qname +
                         (hint.empty() ? " (one of " + all + ")" : hint));
        return std::nullopt;
      }
      cmp.enum_value = static_cast<int>(it - names.begin());
    } else {
      std::optional<double> n = ParseScalar(qname, QuantityUnit(*quantity));
      if (!n) return std::nullopt;
      cmp.number = *n;
    }
    c.text = TextBetween(q.pos, Peek());
    return c;
  }

  static std::string JoinQuantities() {
    std::string out;
    for (const auto& n : QuantityNames()) out += (out.empty() ? "" : ", ") + n;
    return out;
  }

  std::string_view text_;
  const ParseOptions& options_;
  std::vector<Token> tokens_;
  std::vector<std::string_view> lines_;
  std::size_t i_ = 0;
  std::vector<ParseError> errors_;
  int error_count_ = 0;
  Sequence seq_;
  std::map<std::string, int> definitions_;  // TARGET and CONST names -> line
  std::set<std::string> used_overrides_;
  std::set<std::string> broken_definitions_;  // TARGET and CONST names whose value had an error
  int abort_line_ = 0;
};

}  // namespace

std::string ParseError::ToString(const std::string& source) const {
  if (pos.line <= 0) return source + ": " + message;
  return source + ":" + std::to_string(pos.line) + ":" + std::to_string(pos.column) + ": " +
         message;
}

ParseReport ParseSequenceText(std::string_view text, const ParseOptions& options) {
  return Parser(text, options).Run();
}

Result<Sequence> ParseSequence(std::string_view text, const ParseOptions& options) {
  ParseReport r = ParseSequenceText(text, options);
  if (r.ok()) return std::move(*r.sequence);
  std::string m = r.errors.front().ToString(options.source);
  if (r.errors.size() > 1) {
    m += " (and " + std::to_string(r.errors.size() - 1) + " more error" +
         (r.errors.size() > 2 ? "s" : "") + ")";
  }
  return InvalidArgument(m);
}

Result<Sequence> ParseSequenceFile(const std::string& path, ParseOptions options) {
  std::ifstream in(path);
  if (!in) return NotFound("cannot read sequence file '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  if (options.source.empty() || options.source == ParseOptions{}.source) options.source = path;
  return ParseSequence(text.str(), options);
}

std::string FormatErrors(const ParseReport& report, const std::string& source) {
  std::string out;
  for (const auto& e : report.errors) out += e.ToString(source) + "\n";
  return out;
}

}  // namespace rover::apl::sequencer
