// The float polynomials of src/core/float_math.hpp in GLSL, statement for statement, so that a
// shader computes the CPU's cosine and exponential rather than the GPU's built-in cos and exp,
// whose precision GLSL leaves to the implementation (Vulkan allows an absolute error of 2^-11 in
// cos; SwiftShader's, in the browser, differs from the CPU's by 2e-4). The constants
// FLOAT_MATH_TWO_PI, FLOAT_MATH_EXP_FLOOR and FLOAT_MATH_EXP_CEILING are declared before this file
// from the C++ ones (float_math_source() in random.cpp). Tests compare the two bit for bit.

// cos(2 pi t) for t in turns (cos_turns).
float cos_turns(float t) {
  t -= float(int(t));
  t = abs(t);
  t = t > 0.5 ? 1.0 - t : t;
  float sign = t > 0.25 ? -1.0 : 1.0;
  t = t > 0.25 ? 0.5 - t : t;
  precise float x = FLOAT_MATH_TWO_PI * t;
  precise float x2 = x * x;
  precise float p =
      1.0 + x2 * (-1.0 / 2.0 +
                  x2 * (1.0 / 24.0 +
                        x2 * (-1.0 / 720.0 +
                              x2 * (1.0 / 40320.0 +
                                    x2 * (-1.0 / 3628800.0 + x2 * (1.0 / 479001600.0))))));
  return sign * p;
}

// e^x as Cephes' expf (exp_float): 0 below FLOAT_MATH_EXP_FLOOR; x must not be NaN.
float exp_float(float x) {
  float clamped = clamp(x, FLOAT_MATH_EXP_FLOOR, FLOAT_MATH_EXP_CEILING);
  precise float t = clamped * 1.44269504088896341;
  int k = int(t + (t < 0.0 ? -0.5 : 0.5));
  float kf = float(k);
  precise float r = (clamped - kf * 0.693359375) - kf * -2.12194440e-4;
  precise float r2 = r * r;
  precise float p = ((((((1.9875691500e-4 * r + 1.3981999507e-3) * r + 8.3334519073e-3) * r +
                        4.1665795894e-2) *
                           r +
                       1.6666665459e-1) *
                          r +
                      5.0000001201e-1) *
                         r2 +
                     r) +
                    1.0;
  float scale = uintBitsToFloat(uint(k + 127) << 23u);
  return x < FLOAT_MATH_EXP_FLOOR ? 0.0 : p * scale;
}
