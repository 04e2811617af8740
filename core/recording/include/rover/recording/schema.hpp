#pragma once
/// @file
/// The schema of a recorded topic: its IDL type name and one self-contained OMG IDL text, built
/// from the IDL files embedded into the build (rover/idl/idl_sources.hpp). MCAP's `omgidl`
/// schema encoding asks for every include resolved and no preprocessor directives, so the text
/// is the type's file with the files it includes put first (each once, in include order) and
/// every `#...` line left out; comments stay. Foxglove and Lichtblick parse it and decode the
/// CDR messages of the channel with the type the schema name names.

#include <span>
#include <string>
#include <string_view>

#include "rover/base/status.hpp"
#include "rover/idl/idl_sources.hpp"

namespace rover::recording {

/// MCAP's name of the schema encoding.
inline constexpr const char* kOmgIdl = "omgidl";

struct TopicSchema {
  std::string name;  ///< the scoped IDL type name, "rover::dl::PoseEstimate"
  std::string text;  ///< self-contained IDL
};

/// `file` with its includes resolved among `files` (see the file comment). Errors: a file that
/// is not among them ("rover_dl.idl includes rover_x.idl, which is not an IDL file of this
/// build"), an include cycle, an include line without a quoted name.
Result<std::string> ResolveIdl(std::string_view file, std::span<const idl::IdlFile> files);

/// The catalog's @topic type with idlc C name `c_name` ("rover_dl_PoseEstimate"); NotFound if
/// none.
Result<idl::IdlTopicType> FindTopicType(std::string_view c_name);

/// The schema of the @topic type `c_name`, from this build's IDL files.
Result<TopicSchema> SchemaForType(std::string_view c_name);

/// `text` without comments, with one space between words and none around punctuation: two IDL
/// texts that differ only in comments and layout normalise to the same string.
std::string NormalizeIdl(std::string_view text);

}  // namespace rover::recording
