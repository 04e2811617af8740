// PDS3 (ODL) label reader for camera models and coordinate-system states (pds_label.hpp).

#include "rover/geometry/pds_label.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>

namespace rover::geometry {
namespace {

// One `KEY = VALUE` statement.
struct Statement {
  std::string key;
  std::string value;  // raw text, may span lines
  int line = 0;
};

// A GROUP or OBJECT (or the top level, name "") and its own statements.
struct Block {
  std::string name;
  int line = 0;
  std::vector<Statement> statements;

  const Statement* Find(std::string_view key) const {
    for (const Statement& s : statements) {
      if (s.key == key) return &s;
    }
    return nullptr;
  }
};

bool IsSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f'; }

std::string Trim(std::string_view s) {
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && IsSpace(s[b])) ++b;
  while (e > b && IsSpace(s[e - 1])) --e;
  return std::string(s.substr(b, e - b));
}

std::string Unquote(std::string_view s) {
  std::string t = Trim(s);
  if (t.size() >= 2 && t.front() == '"' && t.back() == '"') t = t.substr(1, t.size() - 2);
  return Trim(t);
}

// Splits the label into blocks of statements. Errors name the line.
Result<std::vector<Block>> Lex(std::string_view text, const std::string& source) {
  std::vector<Block> blocks(1);   // blocks[0] = top level
  std::vector<std::size_t> open;  // stack of indices into blocks
  std::size_t i = 0;
  int line = 1;
  const auto current = [&]() -> Block& { return blocks[open.empty() ? 0 : open.back()]; };
  const auto advance = [&]() {
    if (text[i] == '\n') ++line;
    ++i;
  };
  while (i < text.size()) {
    // Skip white space and comments.
    if (IsSpace(text[i])) {
      advance();
      continue;
    }
    if (text.compare(i, 2, "/*") == 0) {
      const int start = line;
      while (i < text.size() && text.compare(i, 2, "*/") != 0) advance();
      if (i >= text.size()) {
        return InvalidArgument(source + ":" + std::to_string(start) + ": unterminated comment");
      }
      i += 2;
      continue;
    }
    // Key.
    const int key_line = line;
    const std::size_t key_begin = i;
    while (i < text.size() && !IsSpace(text[i]) && text[i] != '=') ++i;
    const std::string key(text.substr(key_begin, i - key_begin));
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t' || text[i] == '\r')) ++i;
    if (key == "END" && (i >= text.size() || text[i] != '=')) break;
    if (i >= text.size() || text[i] != '=') {
      return InvalidArgument(source + ":" + std::to_string(key_line) + ": expected '=' after '" +
                             key + "'");
    }
    ++i;
    // Value: up to the end of the line, continuing while inside quotes or brackets.
    while (i < text.size() && (text[i] == ' ' || text[i] == '\t')) ++i;
    const std::size_t value_begin = i;
    int depth = 0;
    bool quoted = false;
    while (i < text.size()) {
      const char c = text[i];
      if (c == '"') {
        quoted = !quoted;
      } else if (!quoted) {
        if (c == '(' || c == '{') ++depth;
        if (c == ')' || c == '}') --depth;
        if (c == '\n' && depth <= 0) break;
        if (depth <= 0 && text.compare(i, 2, "/*") == 0) break;
      }
      advance();
    }
    if (quoted || depth > 0) {
      return InvalidArgument(source + ":" + std::to_string(key_line) + ": " + key +
                             ": unterminated " + (quoted ? "string" : "parenthesis"));
    }
    const std::string value = Trim(text.substr(value_begin, i - value_begin));
    if (key == "GROUP" || key == "OBJECT") {
      blocks.push_back(Block{Unquote(value), key_line, {}});
      open.push_back(blocks.size() - 1);
    } else if (key == "END_GROUP" || key == "END_OBJECT") {
      if (open.empty()) {
        return InvalidArgument(source + ":" + std::to_string(key_line) + ": " + key +
                               " without a matching GROUP/OBJECT");
      }
      open.pop_back();
    } else {
      current().statements.push_back(Statement{key, value, key_line});
    }
  }
  return blocks;
}

// "file:line: GROUP.KEY: message".
Status KeyError(const std::string& source, const Block& block, const Statement& s,
                const std::string& message) {
  return InvalidArgument(source + ":" + std::to_string(s.line) + ": " +
                         (block.name.empty() ? "" : block.name + ".") + s.key + ": " + message);
}

Status MissingKey(const std::string& source, const Block& block, std::string_view key) {
  return InvalidArgument(source + ":" + std::to_string(block.line) + ": " +
                         (block.name.empty() ? "" : block.name + ".") + std::string(key) +
                         ": missing");
}

// Parses "(a, b, c)" or "a" (units "<...>" allowed after each number).
std::optional<std::vector<double>> ParseNumbers(std::string_view value) {
  std::string t = Trim(value);
  if (!t.empty() && t.front() == '(') {
    if (t.back() != ')') return std::nullopt;
    t = t.substr(1, t.size() - 2);
  }
  std::vector<double> out;
  std::size_t pos = 0;
  while (true) {
    const std::size_t comma = t.find(',', pos);
    std::string item = Trim(std::string_view(t).substr(
        pos, comma == std::string::npos ? std::string::npos : comma - pos));
    const std::size_t unit = item.find('<');
    if (unit != std::string::npos) item = Trim(std::string_view(item).substr(0, unit));
    double d = 0.0;
    const char* begin = item.data();
    const char* end = item.data() + item.size();
    if (item.empty()) return std::nullopt;
    const auto [ptr, ec] = std::from_chars(begin, end, d);
    if (ec != std::errc() || ptr != end || !std::isfinite(d)) return std::nullopt;
    out.push_back(d);
    if (comma == std::string::npos) break;
    pos = comma + 1;
  }
  return out;
}

std::string Shorten(const std::string& value) {
  std::string flat;
  for (const char c : value) {
    if (c == '\n' || c == '\r') continue;
    if (IsSpace(c) && !flat.empty() && flat.back() == ' ') continue;
    flat.push_back(IsSpace(c) ? ' ' : c);
  }
  return flat.size() > 80 ? flat.substr(0, 77) + "..." : flat;
}

Result<std::vector<double>> Numbers(const std::string& source, const Block& block,
                                    std::string_view key, std::size_t count) {
  const Statement* s = block.Find(key);
  if (s == nullptr) return MissingKey(source, block, key);
  const auto numbers = ParseNumbers(s->value);
  if (!numbers || numbers->size() != count) {
    return KeyError(source, block, *s,
                    "expected " + std::to_string(count) + " number" + (count > 1 ? "s" : "") +
                        ", got '" + Shorten(s->value) + "'");
  }
  return *numbers;
}

Result<Eigen::Vector3d> Vector3(const std::string& source, const Block& block,
                                std::string_view key) {
  auto n = Numbers(source, block, key, 3);
  if (!n.ok()) return n.status();
  return Eigen::Vector3d((*n)[0], (*n)[1], (*n)[2]);
}

Result<int> Integer(const std::string& source, const Block& block, std::string_view key) {
  auto n = Numbers(source, block, key, 1);
  if (!n.ok()) return n.status();
  const double d = (*n)[0];
  if (d != std::floor(d) || std::abs(d) > 1e9) {
    return KeyError(source, block, *block.Find(key),
                    "expected an integer, got '" + Shorten(block.Find(key)->value) + "'");
  }
  return static_cast<int>(d);
}

const Block* FindBlock(const std::vector<Block>& blocks, std::string_view name) {
  for (std::size_t b = 1; b < blocks.size(); ++b) {
    if (blocks[b].name == name) return &blocks[b];
  }
  return nullptr;
}

Result<CameraModel> ParseModel(const std::string& source, const Block& g, const std::string& type,
                               int width, int height) {
  const auto fail = [&](const Status& s) {
    return s.WithPrefix(source + ":" + std::to_string(g.line) + ": " + g.name);
  };
  auto c = Vector3(source, g, "MODEL_COMPONENT_1");
  if (!c.ok()) return c.status();
  auto a = Vector3(source, g, "MODEL_COMPONENT_2");
  if (!a.ok()) return a.status();
  auto h = Vector3(source, g, "MODEL_COMPONENT_3");
  if (!h.ok()) return h.status();
  auto v = Vector3(source, g, "MODEL_COMPONENT_4");
  if (!v.ok()) return v.status();
  if (type == "CAHV") {
    auto m = CameraModel::Create(Cahv{*c, *a, *h, *v}, width, height);
    if (!m.ok()) return fail(m.status());
    return m;
  }
  auto o = Vector3(source, g, "MODEL_COMPONENT_5");
  if (!o.ok()) return o.status();
  auto r = Vector3(source, g, "MODEL_COMPONENT_6");
  if (!r.ok()) return r.status();
  if (type == "CAHVOR") {
    auto m = CameraModel::Create(Cahvor{*c, *a, *h, *v, *o, *r}, width, height);
    if (!m.ok()) return fail(m.status());
    return m;
  }
  auto e = Vector3(source, g, "MODEL_COMPONENT_7");
  if (!e.ok()) return e.status();
  auto t = Integer(source, g, "MODEL_COMPONENT_8");
  if (!t.ok()) return t.status();
  auto p = Numbers(source, g, "MODEL_COMPONENT_9", 1);
  if (!p.ok()) return p.status();
  if (*t < 1 || *t > 3) {
    return KeyError(source, g, *g.Find("MODEL_COMPONENT_8"),
                    "CAHVORE type " + std::to_string(*t) +
                        " is not 1 (perspective), 2 (fisheye) or 3 (general)");
  }
  Cahvore m{*c, *a, *h, *v, *o, *r, *e, static_cast<CahvoreType>(*t), (*p)[0]};
  auto model = CameraModel::Create(m, width, height);
  if (!model.ok()) return fail(model.status());
  return model;
}

}  // namespace

Eigen::Isometry3d PdsCoordinateSystem::ReferenceFromFrame() const {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = origin_rotation.normalized().toRotationMatrix();
  t.translation() = origin_offset;
  return t;
}

const PdsCoordinateSystem* PdsCameraLabel::FindByName(std::string_view name) const {
  for (const PdsCoordinateSystem& cs : coordinate_systems) {
    if (cs.name == name) return &cs;
  }
  return nullptr;
}

const PdsCoordinateSystem* PdsCameraLabel::FindByGroup(std::string_view group) const {
  for (const PdsCoordinateSystem& cs : coordinate_systems) {
    if (cs.group == group) return &cs;
  }
  return nullptr;
}

Eigen::Isometry3d RoverFromMslNav() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal();
  return t;
}

Result<PdsCameraLabel> ParsePdsCameraLabel(std::string_view text, const std::string& source) {
  auto lexed = Lex(text, source);
  if (!lexed.ok()) return lexed.status();
  const std::vector<Block>& blocks = *lexed;

  // Image size.
  const Block* image = FindBlock(blocks, "IMAGE");
  if (image == nullptr) {
    return InvalidArgument(source + ": no OBJECT = IMAGE (needed for the image size)");
  }
  auto width = Integer(source, *image, "LINE_SAMPLES");
  if (!width.ok()) return width.status();
  auto height = Integer(source, *image, "LINES");
  if (!height.ok()) return height.status();
  if (*width < 1 || *height < 1) {
    return KeyError(source, *image, *image->Find("LINES"),
                    "image size " + std::to_string(*width) + "x" + std::to_string(*height) +
                        " must be at least 1x1");
  }

  // Camera model.
  const Block* g = FindBlock(blocks, "GEOMETRIC_CAMERA_MODEL_PARMS");
  if (g == nullptr) return InvalidArgument(source + ": no GROUP = GEOMETRIC_CAMERA_MODEL_PARMS");
  const Statement* type_statement = g->Find("MODEL_TYPE");
  if (type_statement == nullptr) return MissingKey(source, *g, "MODEL_TYPE");
  const std::string type = Unquote(type_statement->value);
  if (type != "CAHV" && type != "CAHVOR" && type != "CAHVORE") {
    return KeyError(source, *g, *type_statement,
                    "unsupported model type '" + type + "' (expected CAHV, CAHVOR or CAHVORE)");
  }
  auto model = ParseModel(source, *g, type, *width, *height);
  if (!model.ok()) return model.status();

  PdsCameraLabel label{source, type, "", {}, *model, {}};
  if (const Statement* s = g->Find("REFERENCE_COORD_SYSTEM_NAME")) {
    label.model_frame = Unquote(s->value);
  }
  if (const Statement* s = g->Find("REFERENCE_COORD_SYSTEM_INDEX")) {
    const auto index = ParseNumbers(s->value);
    if (!index)
      return KeyError(source, *g, *s, "expected integers, got '" + Shorten(s->value) + "'");
    for (const double d : *index) label.model_frame_index.push_back(static_cast<int>(d));
  }

  // Coordinate-system states.
  for (const Block& b : blocks) {
    const Statement* offset_statement = b.Find("ORIGIN_OFFSET_VECTOR");
    if (offset_statement == nullptr) continue;
    PdsCoordinateSystem cs;
    cs.group = b.name;
    cs.line = offset_statement->line;
    auto offset = Vector3(source, b, "ORIGIN_OFFSET_VECTOR");
    if (!offset.ok()) return offset.status();
    cs.origin_offset = *offset;
    auto q = Numbers(source, b, "ORIGIN_ROTATION_QUATERNION", 4);
    if (!q.ok()) return q.status();
    const Eigen::Quaterniond quat((*q)[0], (*q)[1], (*q)[2], (*q)[3]);
    if (std::abs(quat.norm() - 1.0) > 1e-3) {
      return KeyError(source, b, *b.Find("ORIGIN_ROTATION_QUATERNION"),
                      "quaternion norm " + std::to_string(quat.norm()) + " is not 1 (within 1e-3)");
    }
    cs.origin_rotation = quat.normalized();
    if (const Statement* s = b.Find("COORDINATE_SYSTEM_NAME")) cs.name = Unquote(s->value);
    if (const Statement* s = b.Find("REFERENCE_COORD_SYSTEM_NAME")) {
      cs.reference_name = Unquote(s->value);
    }
    label.coordinate_systems.push_back(std::move(cs));
  }
  return label;
}

Result<PdsCameraLabel> ReadPdsCameraLabel(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return NotFound(path + ": cannot open the PDS label");
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) return Unavailable(path + ": read error");
  return ParsePdsCameraLabel(ss.str(), path);
}

}  // namespace rover::geometry
