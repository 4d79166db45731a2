// What GLSL ES 3.00, HLSL and Metal lack of the GLSL 4.50 the methods are written in, written in
// what they have: cross_compile.cpp puts it before a method's library when it cross-compiles it.
// Each replacement gives the same bits as the built-in it stands for.

// umulExtended (GLSL 4.00 and GLSL ES 3.10; SPIRV-Cross 2021 writes it unchanged into HLSL, which
// has no such function): the 64-bit product of two uints, from four 16 x 16-bit partial products
// that are exact in 32 bits. The high word adds their high halves and the carry out of the middle
// column, which is below 3 * 2^16.
void stochtex_umul_extended(uint a, uint b, out uint msb, out uint lsb) {
  uint a0 = a & 0xffffu;
  uint a1 = a >> 16u;
  uint b0 = b & 0xffffu;
  uint b1 = b >> 16u;
  uint low_low = a0 * b0;
  uint low_high = a0 * b1;
  uint high_low = a1 * b0;
  uint middle = (low_low >> 16u) + (low_high & 0xffffu) + (high_low & 0xffffu);
  msb = a1 * b1 + (low_high >> 16u) + (high_low >> 16u) + (middle >> 16u);
  lsb = a * b;
}
#define umulExtended stochtex_umul_extended
