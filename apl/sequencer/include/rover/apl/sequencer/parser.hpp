#pragma once
/// @file
/// The sequence language's parser (the grammar is in apl/sequencer/README.md). It checks a
/// whole text against the grammar and the command table and returns either a Sequence or every
/// error it found (up to ParseOptions::max_errors), each with its line and column; a text with
/// any error yields no Sequence, so nothing of it can run.
///
/// Messages name what is wrong and, where it helps, the closest known name:
///   approach.seq:7:1: unknown command 'DRIV ARC' (did you mean 'DRIVE ARC'?)
///   approach.seq:9:16: distance = 60 m is outside [-50, 50]
///   approach.seq:12:1: unbounded loop: WHILE needs MAX n (the most times the body runs)

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rover/apl/sequencer/sequence.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::sequencer {

struct ParseOptions {
  /// The name messages start with ("deploy/sequences/approach_template.seq").
  std::string source = "sequence";
  /// Values that replace TARGET and CONST definitions of the text, written as in the language:
  /// {"target", "(5.2, 0.4, 0)"}, {"coarse_step", "20 cm"}. A name the text does not define is
  /// an error. This is how one template file serves many runs.
  std::map<std::string, std::string> overrides;
  /// Errors after this many are not reported (the parse still fails).
  int max_errors = 20;
};

struct ParseError {
  SourcePos pos;  ///< line 0: not in the text (an override)
  std::string message;

  /// "<source>:<line>:<column>: <message>" ("<source>: <message>" for line 0).
  std::string ToString(const std::string& source) const;
};

struct ParseReport {
  std::optional<Sequence> sequence;  ///< set exactly when `errors` is empty
  std::vector<ParseError> errors;
  bool ok() const { return errors.empty(); }
};

/// Parses `text`; see the file comment.
ParseReport ParseSequenceText(std::string_view text, const ParseOptions& options = {});

/// The sequence, or InvalidArgument whose message is the first error
/// ("<source>:<line>:<col>: <message>") followed by " (and N more errors)" when there are more.
Result<Sequence> ParseSequence(std::string_view text, const ParseOptions& options = {});

/// Reads and parses a file; `options.source` defaults to `path`. Errors: NotFound when the file
/// cannot be read, else as ParseSequence.
Result<Sequence> ParseSequenceFile(const std::string& path, ParseOptions options = {});

/// Every error of a report, one "<source>:<line>:<col>: <message>" per line.
std::string FormatErrors(const ParseReport& report, const std::string& source);

}  // namespace rover::apl::sequencer
