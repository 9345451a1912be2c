#include "lookout/io/ros_message.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cstring>
#include <limits>
#include <set>
#include <utility>

#include <fmt/format.h>

#include "lookout/io/little_endian.h"

namespace lookout::io {
namespace {

struct PrimitiveName {
  std::string_view name;
  RosType type;
};

// `byte` and `char` are ROS1's deprecated aliases of int8 and uint8.
constexpr std::array<PrimitiveName, 17> kPrimitives{{
    {"bool", RosType::kBool},       {"int8", RosType::kInt8},
    {"uint8", RosType::kUint8},     {"byte", RosType::kInt8},
    {"char", RosType::kUint8},      {"int16", RosType::kInt16},
    {"uint16", RosType::kUint16},   {"int32", RosType::kInt32},
    {"uint32", RosType::kUint32},   {"int64", RosType::kInt64},
    {"uint64", RosType::kUint64},   {"float32", RosType::kFloat32},
    {"float64", RosType::kFloat64}, {"string", RosType::kString},
    {"time", RosType::kTime},       {"duration", RosType::kDuration},
    {"Header", RosType::kMessage},
}};

std::string_view Trim(std::string_view s) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!s.empty() && blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && blank(s.back())) s.remove_suffix(1);
  return s;
}

bool IsSeparator(std::string_view line) {
  line = Trim(line);
  return line.size() >= 3 && std::all_of(line.begin(), line.end(), [](char c) { return c == '='; });
}

bool IsIdentifier(std::string_view s) {
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s.front()))) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
  });
}

bool IsTypeName(std::string_view s) {
  const std::size_t slash = s.find('/');
  if (slash == std::string_view::npos) return IsIdentifier(s);
  return IsIdentifier(s.substr(0, slash)) && IsIdentifier(s.substr(slash + 1));
}

std::size_t FixedSize(RosType type) {
  switch (type) {
    case RosType::kBool:
    case RosType::kInt8:
    case RosType::kUint8:
      return 1;
    case RosType::kInt16:
    case RosType::kUint16:
      return 2;
    case RosType::kInt32:
    case RosType::kUint32:
    case RosType::kFloat32:
      return 4;
    case RosType::kInt64:
    case RosType::kUint64:
    case RosType::kFloat64:
    case RosType::kTime:
    case RosType::kDuration:
      return 8;
    case RosType::kString:
      return 4;  // the length word; the characters are counted as they come
    case RosType::kMessage:
      break;
  }
  return 0;
}

// Checks a constant's value the way the ROS message generators would accept it.
bool ValidConstant(RosType type, std::string_view value) {
  const auto integer_in = [&](auto lowest, auto highest) {
    std::int64_t v = 0;
    std::uint64_t u = 0;
    if (!value.empty() && value.front() == '-') {
      const auto r = std::from_chars(value.data(), value.data() + value.size(), v);
      return r.ec == std::errc() && r.ptr == value.data() + value.size() &&
             v >= static_cast<std::int64_t>(lowest);
    }
    const auto r = std::from_chars(value.data(), value.data() + value.size(), u);
    return r.ec == std::errc() && r.ptr == value.data() + value.size() &&
           u <= static_cast<std::uint64_t>(highest);
  };
  switch (type) {
    case RosType::kBool:
      return value == "True" || value == "False" || value == "true" || value == "false" ||
             value == "1" || value == "0";
    case RosType::kInt8:
      return integer_in(std::numeric_limits<std::int8_t>::min(),
                        std::numeric_limits<std::int8_t>::max());
    case RosType::kUint8:
      return integer_in(0, std::numeric_limits<std::uint8_t>::max());
    case RosType::kInt16:
      return integer_in(std::numeric_limits<std::int16_t>::min(),
                        std::numeric_limits<std::int16_t>::max());
    case RosType::kUint16:
      return integer_in(0, std::numeric_limits<std::uint16_t>::max());
    case RosType::kInt32:
      return integer_in(std::numeric_limits<std::int32_t>::min(),
                        std::numeric_limits<std::int32_t>::max());
    case RosType::kUint32:
      return integer_in(0, std::numeric_limits<std::uint32_t>::max());
    case RosType::kInt64:
      return integer_in(std::numeric_limits<std::int64_t>::min(),
                        std::numeric_limits<std::int64_t>::max());
    case RosType::kUint64:
      return integer_in(0, std::numeric_limits<std::uint64_t>::max());
    case RosType::kFloat32:
    case RosType::kFloat64: {
      double d = 0.0;
      const auto r = std::from_chars(value.data(), value.data() + value.size(), d);
      return r.ec == std::errc() && r.ptr == value.data() + value.size();
    }
    case RosType::kString:
      return true;
    case RosType::kTime:
    case RosType::kDuration:
    case RosType::kMessage:
      break;
  }
  return false;
}

// One "type name" or "type NAME=value" line of the section defining `spec`.
void ParseLine(std::string_view line, const std::string& package, RosMessageSpec& spec,
               const std::string& where) {
  const auto fail = [&](const std::string& problem) { throw RosMessageError(where, problem); };
  const std::size_t type_end = line.find_first_of(" \t");
  if (type_end == std::string_view::npos) fail(fmt::format("'{}' has a type but no name", line));
  std::string_view type_text = line.substr(0, type_end);
  std::string_view rest = Trim(line.substr(type_end));

  RosField field;
  if (const std::size_t bracket = type_text.find('['); bracket != std::string_view::npos) {
    if (type_text.back() != ']') fail(fmt::format("bad array type '{}'", type_text));
    const std::string_view length = type_text.substr(bracket + 1, type_text.size() - bracket - 2);
    type_text = type_text.substr(0, bracket);
    if (length.empty()) {
      field.array = RosArray::kVariable;
    } else {
      const auto r = std::from_chars(length.data(), length.data() + length.size(),
                                     field.fixed_length);
      if (r.ec != std::errc() || r.ptr != length.data() + length.size()) {
        fail(fmt::format("bad array length '{}'", length));
      }
      field.array = RosArray::kFixed;
    }
  }
  const auto primitive = std::find_if(kPrimitives.begin(), kPrimitives.end(),
                                      [&](const PrimitiveName& p) { return p.name == type_text; });
  if (primitive != kPrimitives.end()) {
    field.type = primitive->type;
    if (type_text == "Header") field.message_type = "std_msgs/Header";
  } else if (IsTypeName(type_text)) {
    field.type = RosType::kMessage;
    field.message_type = type_text.find('/') == std::string_view::npos
                             ? fmt::format("{}/{}", package, type_text)
                             : std::string(type_text);
  } else {
    fail(fmt::format("bad type '{}'", type_text));
  }

  if (const std::size_t equals = rest.find('='); equals != std::string_view::npos &&
                                                  rest.substr(0, equals).find('#') ==
                                                      std::string_view::npos) {
    RosConstant constant;
    constant.name = std::string(Trim(rest.substr(0, equals)));
    std::string_view value = rest.substr(equals + 1);
    if (field.type != RosType::kString) value = value.substr(0, value.find('#'));
    value = Trim(value);
    if (!IsIdentifier(constant.name)) fail(fmt::format("bad constant name '{}'", constant.name));
    if (field.array != RosArray::kNone || field.type == RosType::kMessage ||
        field.type == RosType::kTime || field.type == RosType::kDuration) {
      fail(fmt::format("constant {} must have a number, bool or string type", constant.name));
    }
    if (!ValidConstant(field.type, value)) {
      fail(fmt::format("bad value '{}' for constant {} of type {}", value, constant.name,
                       type_text));
    }
    constant.type = field.type;
    constant.value = std::string(value);
    spec.constants.push_back(std::move(constant));
    return;
  }
  const std::size_t name_end = rest.find_first_of(" \t#");
  field.name = std::string(rest.substr(0, name_end));
  if (!IsIdentifier(field.name)) fail(fmt::format("bad field name '{}'", field.name));
  if (name_end != std::string_view::npos) {
    const std::string_view after = Trim(rest.substr(name_end));
    if (!after.empty() && after.front() != '#') {
      fail(fmt::format("unexpected '{}' after field {}", after, field.name));
    }
  }
  if (spec.FieldIndex(field.name)) fail(fmt::format("field {} defined twice", field.name));
  spec.fields.push_back(std::move(field));
}

std::string PackageOf(std::string_view type_name) {
  return std::string(type_name.substr(0, type_name.find('/')));
}

// Every used type defined, none containing itself (ROS forbids it; decoding would not end).
void CheckTypes(const RosMessageDefinition& definition) {
  std::set<std::string> done;
  std::vector<std::string> stack;
  const auto visit = [&](const auto& self, const std::string& name) -> void {
    if (done.count(name) != 0) return;
    if (std::find(stack.begin(), stack.end(), name) != stack.end()) {
      throw RosMessageError(fmt::format("MSG: {}", name), "the type contains itself");
    }
    stack.push_back(name);
    for (const RosField& field : definition.specs.at(name).fields) {
      if (field.type != RosType::kMessage) continue;
      if (definition.specs.count(field.message_type) == 0) {
        throw RosMessageError(fmt::format("MSG: {}", name),
                              fmt::format("field {} has type {}, which the definition lacks",
                                          field.name, field.message_type));
      }
      self(self, field.message_type);
    }
    stack.pop_back();
    done.insert(name);
  };
  for (const auto& [name, spec] : definition.specs) visit(visit, name);
}

std::size_t SaturatingAdd(std::size_t a, std::size_t b) {
  return a > std::numeric_limits<std::size_t>::max() - b ? std::numeric_limits<std::size_t>::max()
                                                         : a + b;
}

std::size_t SaturatingMul(std::size_t a, std::size_t b) {
  return (a != 0 && b > std::numeric_limits<std::size_t>::max() / a)
             ? std::numeric_limits<std::size_t>::max()
             : a * b;
}

std::size_t ElementMinimumSize(const RosMessageDefinition& definition, const RosField& field) {
  return field.type == RosType::kMessage
             ? MinimumSerializedSize(definition, field.message_type)
             : FixedSize(field.type);
}

class Decoder {
 public:
  Decoder(const RosMessageDefinition& definition, std::string_view bytes)
      : definition_(definition), bytes_(bytes) {}

  RosValue Message(const std::string& type_name, int depth) {
    if (depth > kMaxRosNesting) {
      throw RosMessageError("", fmt::format("nested deeper than {}", kMaxRosNesting));
    }
    const RosMessageSpec& spec = definition_.specs.at(type_name);
    RosStruct s;
    s.spec = &spec;
    s.fields.reserve(spec.fields.size());
    for (const RosField& field : spec.fields) {
      try {
        s.fields.push_back(Field(field, depth));
      } catch (const RosMessageError& e) {
        throw e.Within(field.name);
      }
    }
    return RosValue{std::move(s)};
  }

  std::size_t left() const { return bytes_.size() - pos_; }

 private:
  const char* Take(std::size_t n) {
    if (n > left()) {
      throw RosMessageError("", fmt::format("needs {} bytes at byte {}, {} left", n, pos_, left()));
    }
    const char* p = bytes_.data() + pos_;
    pos_ += n;
    return p;
  }

  std::uint32_t Count() { return LoadLittleEndian<std::uint32_t>(Take(4)); }

  RosValue Scalar(const RosField& field, int depth) {
    switch (field.type) {
      case RosType::kBool: {
        const auto b = static_cast<unsigned char>(*Take(1));
        if (b > 1) throw RosMessageError("", fmt::format("bool byte is {}, not 0 or 1", b));
        return RosValue{b == 1};
      }
      case RosType::kInt8:
        return RosValue{std::int64_t{LoadLittleEndian<std::int8_t>(Take(1))}};
      case RosType::kUint8:
        return RosValue{std::uint64_t{LoadLittleEndian<std::uint8_t>(Take(1))}};
      case RosType::kInt16:
        return RosValue{std::int64_t{LoadLittleEndian<std::int16_t>(Take(2))}};
      case RosType::kUint16:
        return RosValue{std::uint64_t{LoadLittleEndian<std::uint16_t>(Take(2))}};
      case RosType::kInt32:
        return RosValue{std::int64_t{LoadLittleEndian<std::int32_t>(Take(4))}};
      case RosType::kUint32:
        return RosValue{std::uint64_t{LoadLittleEndian<std::uint32_t>(Take(4))}};
      case RosType::kInt64:
        return RosValue{LoadLittleEndian<std::int64_t>(Take(8))};
      case RosType::kUint64:
        return RosValue{LoadLittleEndian<std::uint64_t>(Take(8))};
      case RosType::kFloat32:
        return RosValue{static_cast<double>(LoadLittleEndian<float>(Take(4)))};
      case RosType::kFloat64:
        return RosValue{LoadLittleEndian<double>(Take(8))};
      case RosType::kString: {
        const std::uint32_t n = Count();
        return RosValue{std::string(Take(n), n)};
      }
      case RosType::kTime: {
        const char* p = Take(8);
        return RosValue{RosTime{LoadLittleEndian<std::uint32_t>(p),
                                LoadLittleEndian<std::uint32_t>(p + 4)}};
      }
      case RosType::kDuration: {
        const char* p = Take(8);
        return RosValue{RosDuration{LoadLittleEndian<std::int32_t>(p),
                                    LoadLittleEndian<std::int32_t>(p + 4)}};
      }
      case RosType::kMessage:
        return Message(field.message_type, depth + 1);
    }
    throw RosMessageError("", "unknown field type");
  }

  template <typename Wide, typename Narrow>
  std::vector<Wide> Numbers(std::uint32_t count) {
    const char* p = Take(std::size_t{count} * sizeof(Narrow));
    std::vector<Wide> out(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      out[i] = static_cast<Wide>(LoadLittleEndian<Narrow>(p + std::size_t{i} * sizeof(Narrow)));
    }
    return out;
  }

  RosValue Field(const RosField& field, int depth) {
    if (field.array == RosArray::kNone) return Scalar(field, depth);
    const std::uint32_t count = field.array == RosArray::kFixed ? field.fixed_length : Count();
    // Bound the count by the bytes left before anything is allocated for it.
    // Elements of a zero-size type take no bytes, so the bytes cannot bound them: they share
    // one budget per message, which nested arrays of them cannot multiply past.
    const std::size_t element_size = ElementMinimumSize(definition_, field);
    if (element_size == 0) {
      if (count > zero_size_budget_) {
        throw RosMessageError("", fmt::format("more than {} elements of a zero-size type",
                                              kMaxZeroSizeElements));
      }
      zero_size_budget_ -= count;
    } else if (SaturatingMul(count, element_size) > left()) {
      throw RosMessageError("", fmt::format("array of {} elements cannot fit in the {} bytes left",
                                            count, left()));
    }
    switch (field.type) {
      case RosType::kInt8:
        return RosValue{Numbers<std::int64_t, std::int8_t>(count)};
      case RosType::kUint8:
        return RosValue{Numbers<std::uint64_t, std::uint8_t>(count)};
      case RosType::kInt16:
        return RosValue{Numbers<std::int64_t, std::int16_t>(count)};
      case RosType::kUint16:
        return RosValue{Numbers<std::uint64_t, std::uint16_t>(count)};
      case RosType::kInt32:
        return RosValue{Numbers<std::int64_t, std::int32_t>(count)};
      case RosType::kUint32:
        return RosValue{Numbers<std::uint64_t, std::uint32_t>(count)};
      case RosType::kInt64:
        return RosValue{Numbers<std::int64_t, std::int64_t>(count)};
      case RosType::kUint64:
        return RosValue{Numbers<std::uint64_t, std::uint64_t>(count)};
      case RosType::kFloat32:
        return RosValue{Numbers<double, float>(count)};
      case RosType::kFloat64:
        return RosValue{Numbers<double, double>(count)};
      case RosType::kBool:
      case RosType::kString:
      case RosType::kTime:
      case RosType::kDuration:
      case RosType::kMessage:
        break;
    }
    std::vector<RosValue> out;
    out.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      try {
        out.push_back(Scalar(field, depth));
      } catch (const RosMessageError& e) {
        throw e.Within(fmt::format("[{}]", i));
      }
    }
    return RosValue{std::move(out)};
  }

  const RosMessageDefinition& definition_;
  std::string_view bytes_;
  std::size_t pos_ = 0;
  std::uint32_t zero_size_budget_ = kMaxZeroSizeElements;
};

[[noreturn]] void WrongKind(std::string_view wanted) {
  throw RosMessageError("", fmt::format("is not {}", wanted));
}

}  // namespace

RosMessageError::RosMessageError(std::string field, const std::string& problem)
    : std::runtime_error(field.empty() ? problem : fmt::format("{}: {}", field, problem)),
      field_(std::move(field)),
      problem_(problem) {}

RosMessageError RosMessageError::Within(std::string_view outer) const {
  std::string path(outer);
  if (!field_.empty()) {
    if (field_.front() != '[') path += '.';
    path += field_;
  }
  return RosMessageError(std::move(path), problem_);
}

std::optional<std::size_t> RosMessageSpec::FieldIndex(std::string_view field_name) const {
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (fields[i].name == field_name) return i;
  }
  return std::nullopt;
}

RosMessageDefinition ParseRosMessageDefinition(std::string_view type_name, std::string_view text) {
  if (!IsTypeName(type_name) || type_name.find('/') == std::string_view::npos) {
    throw RosMessageError("type", fmt::format("'{}' is not a pkg/Type name", type_name));
  }
  RosMessageDefinition definition;
  definition.root = std::string(type_name);
  std::string current = definition.root;
  RosMessageSpec* spec = &definition.specs[current];
  spec->name = current;
  bool expect_msg_line = false;
  int line_number = 0;
  while (!text.empty()) {
    const std::size_t eol = text.find('\n');
    const std::string_view raw = text.substr(0, eol);
    text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
    ++line_number;
    const std::string where = fmt::format("MSG: {} line {}", current, line_number);
    if (IsSeparator(raw)) {
      expect_msg_line = true;
      continue;
    }
    const std::string_view line = Trim(raw);
    if (line.empty() || line.front() == '#') continue;
    if (expect_msg_line) {
      if (line.substr(0, 4) != "MSG:") {
        throw RosMessageError(where, "a section after '===' must start with 'MSG: pkg/Type'");
      }
      const std::string_view name = Trim(line.substr(4));
      if (!IsTypeName(name) || name.find('/') == std::string_view::npos) {
        throw RosMessageError(where, fmt::format("'{}' is not a pkg/Type name", name));
      }
      current = std::string(name);
      if (definition.specs.count(current) != 0) {
        throw RosMessageError(where, fmt::format("{} is defined twice", current));
      }
      spec = &definition.specs[current];
      spec->name = current;
      expect_msg_line = false;
      continue;
    }
    ParseLine(line, PackageOf(current), *spec, where);
  }
  if (expect_msg_line) {
    throw RosMessageError(fmt::format("line {}", line_number), "the text ends after a '===' line");
  }
  CheckTypes(definition);
  return definition;
}

std::size_t MinimumSerializedSize(const RosMessageDefinition& definition,
                                  std::string_view type_name) {
  // Types are checked acyclic at parse time, so the recursion ends.
  std::size_t total = 0;
  for (const RosField& field : definition.specs.at(std::string(type_name)).fields) {
    switch (field.array) {
      case RosArray::kNone:
        total = SaturatingAdd(total, ElementMinimumSize(definition, field));
        break;
      case RosArray::kFixed:
        total = SaturatingAdd(
            total, SaturatingMul(field.fixed_length, ElementMinimumSize(definition, field)));
        break;
      case RosArray::kVariable:
        total = SaturatingAdd(total, 4);
        break;
    }
  }
  return total;
}

const RosValue& RosStruct::operator[](std::string_view field_name) const {
  const std::optional<std::size_t> i =
      spec == nullptr ? std::nullopt : spec->FieldIndex(field_name);
  if (!i) {
    throw RosMessageError(std::string(field_name),
                          fmt::format("{} has no such field", spec == nullptr ? "?" : spec->name));
  }
  return fields[*i];
}

double RosValue::AsDouble() const {
  if (const auto* d = std::get_if<double>(&data)) return *d;
  if (const auto* i = std::get_if<std::int64_t>(&data)) return static_cast<double>(*i);
  if (const auto* u = std::get_if<std::uint64_t>(&data)) return static_cast<double>(*u);
  WrongKind("a number");
}

std::int64_t RosValue::AsInt() const {
  if (const auto* i = std::get_if<std::int64_t>(&data)) return *i;
  WrongKind("a signed integer");
}

std::uint64_t RosValue::AsUint() const {
  if (const auto* u = std::get_if<std::uint64_t>(&data)) return *u;
  WrongKind("an unsigned integer");
}

bool RosValue::AsBool() const {
  if (const auto* b = std::get_if<bool>(&data)) return *b;
  WrongKind("a bool");
}

const std::string& RosValue::AsString() const {
  if (const auto* s = std::get_if<std::string>(&data)) return *s;
  WrongKind("a string");
}

RosTime RosValue::AsTime() const {
  if (const auto* t = std::get_if<RosTime>(&data)) return *t;
  WrongKind("a time");
}

const std::vector<double>& RosValue::AsDoubles() const {
  if (const auto* v = std::get_if<std::vector<double>>(&data)) return *v;
  WrongKind("an array of floats");
}

const std::vector<RosValue>& RosValue::AsArray() const {
  if (const auto* v = std::get_if<std::vector<RosValue>>(&data)) return *v;
  WrongKind("an array of messages, strings or times");
}

const RosStruct& RosValue::AsStruct() const {
  if (const auto* s = std::get_if<RosStruct>(&data)) return *s;
  WrongKind("a message");
}

RosValue DecodeRosMessage(const RosMessageDefinition& definition, std::string_view bytes) {
  Decoder decoder(definition, bytes);
  RosValue value = decoder.Message(definition.root, 0);
  if (decoder.left() != 0) {
    throw RosMessageError("", fmt::format("{} bytes left over after the message's {} bytes",
                                          decoder.left(), bytes.size() - decoder.left()));
  }
  return value;
}

}  // namespace lookout::io
