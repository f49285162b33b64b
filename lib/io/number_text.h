// Numbers as text for the text output formats (OBJ, USD, CSV): exactly what printf's "%.Pg"
// writes (the shortest of %e and %f for P significant digits, trailing zeros dropped), byte for
// byte, at a fraction of the cost of printf or std::to_chars with a precision (writing guides.obj
// at paper scale took 0.65 G instructions through std::to_chars).
#pragma once

namespace hairfit {

// Writes v as printf("%.*g", precision, v) would, without a terminating NUL, and returns the end.
// `out` needs room for 48 characters (it may be written beyond the end returned); precision must
// be in [1, 17]. Exact: the value's P significant digits are rounded from its exact binary value,
// ties to even, as glibc does.
char* format_general(char* out, double v, int precision);

}  // namespace hairfit
