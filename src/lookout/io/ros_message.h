#pragma once

// ROS1 message definitions and a dynamic decoder of the ROS1 serialisation they describe.
//
// A ROS1 bag's connection records carry the full text of their message type's definition
// (`message_definition`): the root type's fields, then each type it uses after a line of '='
// and a `MSG: pkg/Type` line. Lookout parses that text into RosMessageDefinition and decodes
// messages with it, so a bag is read by what it says it holds, not by layouts compiled in.
// Written by hand: Debian 12 packages no C++ ROS message library outside ROS itself.
//
// The serialisation (ROS wiki "msg" and "ROS/Technical Overview"): little-endian, no padding;
// bool and (u)int8 one byte; time and duration two 32-bit words (sec, nsec; signed for
// duration); string and variable arrays a uint32 count then the elements; fixed arrays the
// elements only; nested messages their fields in order. Constants take no bytes.
//
// Limits, all refused with a RosMessageError: recursive types, nesting deeper than
// kMaxRosNesting, arrays whose count cannot fit in the bytes left (so a corrupted count never
// allocates), more than kMaxZeroSizeElements elements of zero-size types in one message (they
// take no bytes, so nothing else bounds them), bytes left over.

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace lookout::io {

inline constexpr int kMaxRosNesting = 64;
inline constexpr std::uint32_t kMaxZeroSizeElements = 1U << 20;

// A definition that cannot be parsed or a message that does not match its definition.
// `field` locates it: "MSG: pkg/Type line 4" in a definition, "transforms[2].header.stamp" in
// a message.
class RosMessageError : public std::runtime_error {
 public:
  RosMessageError(std::string field, const std::string& problem);
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }
  // The same error one level up: "transforms" + "[2].header" -> "transforms[2].header".
  RosMessageError Within(std::string_view outer) const;

 private:
  std::string field_;
  std::string problem_;
};

enum class RosType : std::uint8_t {
  kBool,
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kInt64,
  kUint64,
  kFloat32,
  kFloat64,
  kString,
  kTime,
  kDuration,
  kMessage,
};

enum class RosArray : std::uint8_t { kNone, kFixed, kVariable };

struct RosField {
  std::string name;
  RosType type = RosType::kMessage;
  std::string message_type;  // "pkg/Type" when type is kMessage
  RosArray array = RosArray::kNone;
  std::uint32_t fixed_length = 0;  // when array is kFixed
};

// `NAME=VALUE` lines: compile-time values, not serialised. The value is kept as written
// (comments and surrounding blanks removed, except in string constants, whose value is the
// whole rest of the line as ROS reads it).
struct RosConstant {
  std::string name;
  RosType type = RosType::kInt32;
  std::string value;
};

struct RosMessageSpec {
  std::string name;  // "pkg/Type"
  std::vector<RosField> fields;
  std::vector<RosConstant> constants;

  std::optional<std::size_t> FieldIndex(std::string_view field_name) const;
};

struct RosMessageDefinition {
  std::string root;                              // "pkg/Type" of the message itself
  std::map<std::string, RosMessageSpec> specs;   // the root and every type it uses

  const RosMessageSpec& Root() const { return specs.at(root); }
};

// Parses `text` as the definition of `type_name` ("pkg/Type"). Field types without a package
// take the enclosing type's package; `Header` is std_msgs/Header. Every message type used must
// be defined in the text, and none may contain itself.
RosMessageDefinition ParseRosMessageDefinition(std::string_view type_name, std::string_view text);

// The smallest serialised size of a `type_name` message (saturating at SIZE_MAX).
std::size_t MinimumSerializedSize(const RosMessageDefinition& definition,
                                  std::string_view type_name);

struct RosTime {
  std::uint32_t sec = 0;
  std::uint32_t nsec = 0;
  bool operator==(const RosTime&) const = default;
};

struct RosDuration {
  std::int32_t sec = 0;
  std::int32_t nsec = 0;
  bool operator==(const RosDuration&) const = default;
};

struct RosValue;

// A decoded message: one value per field of `spec`, in the definition's order.
struct RosStruct {
  const RosMessageSpec* spec = nullptr;
  std::vector<RosValue> fields;

  // Throws RosMessageError naming the field when the type has none of that name.
  const RosValue& operator[](std::string_view field_name) const;
};

// One decoded value. Integers widen to 64 bits and floats to double (exactly); arrays of
// numbers are typed vectors, arrays of anything else vectors of RosValue.
struct RosValue {
  using Data = std::variant<bool, std::int64_t, std::uint64_t, double, std::string, RosTime,
                            RosDuration, std::vector<double>, std::vector<std::int64_t>,
                            std::vector<std::uint64_t>, std::vector<RosValue>, RosStruct>;
  Data data;

  // Typed access; each throws RosMessageError when the value holds another kind.
  double AsDouble() const;  // any number
  std::int64_t AsInt() const;
  std::uint64_t AsUint() const;
  bool AsBool() const;
  const std::string& AsString() const;
  RosTime AsTime() const;
  const std::vector<double>& AsDoubles() const;
  const std::vector<RosValue>& AsArray() const;
  const RosStruct& AsStruct() const;
  const RosValue& operator[](std::string_view field_name) const { return AsStruct()[field_name]; }
};

// Decodes one serialised `definition.root` message; all of `bytes` must be used.
RosValue DecodeRosMessage(const RosMessageDefinition& definition, std::string_view bytes);

}  // namespace lookout::io
