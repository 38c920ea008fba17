// Bindings for scalars.test: every integer width b-script carries as int
// (int8/16, uint8/16, unsigned, enums with small underlying types), double
// fields and parameters, and unary minus (_neg_) on a class. Each is
// reachable as a field (by offset), through a property (getter/setter
// thunks) and as a parameter or result (function thunks), so that sign and
// zero extension is checked on every path.
#include <bscript/Bind.h>
#include <cstdint>

namespace sc {
enum class Small : std::int8_t { minus2 = -2, one = 1 };
enum class Byte : std::uint8_t { low = 3, high = 200 };

struct Bits {
  std::int8_t i8 = -5;
  std::uint8_t u8 = 250;
  std::int16_t i16 = -300;
  std::uint16_t u16 = 65000;
  unsigned u32 = 4000000000u;
  Small small = Small::minus2;
  Byte byte = Byte::high;
  double d = 0.25;
  std::int8_t getI8() const { return i8; }
  void setI8(std::int8_t V) { i8 = V; }
  std::uint16_t getU16() const { return u16; }
  void setU16(std::uint16_t V) { u16 = V; }
};

/// double is 4-aligned inside a struct on i386, 8-aligned on x86-64.
struct Padded {
  char c = 'a';
  double d = 2.5;
};

struct V {
  float x = 0, y = 0;
};
V neg(const V &A) { return {-A.x, -A.y}; }

std::int8_t addI8(std::int8_t A, std::int8_t B) { return std::int8_t(A + B); }
std::uint8_t addU8(std::uint8_t A, std::uint8_t B) { return std::uint8_t(A + B); }
std::int16_t widen16(std::int16_t A) { return A; }
std::uint16_t widenU16(std::uint16_t A) { return A; }
unsigned half(unsigned V) { return V / 2; }
Small flip(Small S) { return S == Small::one ? Small::minus2 : Small::one; }
int byteValue(Byte B) { return int(B); }
double triple(double X) { return 3 * X; }
} // namespace sc

BS_MODULE(Scalars,
  registerEnum<sc::Small>(module, "Small")
    .value("minus2", sc::Small::minus2)
    .value("one", sc::Small::one);
  registerEnum<sc::Byte>(module, "Byte")
    .value("low", sc::Byte::low)
    .value("high", sc::Byte::high);
  registerClass<sc::Bits>(module, "Bits")
    .var<&sc::Bits::i8>("i8")
    .var<&sc::Bits::u8>("u8")
    .var<&sc::Bits::i16>("i16")
    .var<&sc::Bits::u16>("u16")
    .var<&sc::Bits::u32>("u32")
    .var<&sc::Bits::small>("small")
    .var<&sc::Bits::byte>("byte")
    .var<&sc::Bits::d>("d")
    .prop<&sc::Bits::getI8, &sc::Bits::setI8>("pi8")
    .prop<&sc::Bits::getU16, &sc::Bits::setU16>("pu16");
  registerClass<sc::Padded>(module, "Padded")
    .var<&sc::Padded::c>("c")
    .var<&sc::Padded::d>("d");
  registerClass<sc::V>(module, "V")
    .var<&sc::V::x>("x")
    .var<&sc::V::y>("y")
    .func<&sc::neg>("_neg_");
  registerFunction<&sc::addI8>(module, "addI8");
  registerFunction<&sc::addU8>(module, "addU8");
  registerFunction<&sc::widen16>(module, "widen16");
  registerFunction<&sc::widenU16>(module, "widenU16");
  registerFunction<&sc::half>(module, "half");
  registerFunction<&sc::flip>(module, "flip");
  registerFunction<&sc::byteValue>(module, "byteValue");
  registerFunction<&sc::triple>(module, "triple");
)
