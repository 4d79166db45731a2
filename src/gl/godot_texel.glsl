// Godot 3 makes no float32 texture of an imported file (its OpenEXR importer keeps half floats),
// and on Mesa it samples an imported RGBA8 PNG as sRGB (decoded) whatever its import settings,
// so `export-shader --language godot` stores each float image that a library reads texel by
// texel as its floats' bytes in a grey + alpha PNG, which Godot makes a two-channel texture with
// no sRGB form (LA8: read as (L, L, L, A)): float c of texel (x, y) in the texels 8x + 2c (bytes
// 0 and 1, lowest first) and 8x + 2c + 1 (bytes 2 and 3) of row y (ShaderTexture::float_bytes).
// cross_compile puts this before the library for that language only, so that the library's
// texelFetch reads the same floats, bit for bit.

float stochtex_float_of_bytes(sampler2D data, ivec2 first) {
  uvec2 low = uvec2(round(texelFetch(data, first, 0).xw * 255.0));
  uvec2 high = uvec2(round(texelFetch(data, first + ivec2(1, 0), 0).xw * 255.0));
  return uintBitsToFloat(low.x | (low.y << 8u) | (high.x << 16u) | (high.y << 24u));
}

vec4 stochtex_texel_of_bytes(sampler2D data, ivec2 texel) {
  ivec2 first = ivec2(8 * texel.x, texel.y);
  return vec4(stochtex_float_of_bytes(data, first),
              stochtex_float_of_bytes(data, first + ivec2(2, 0)),
              stochtex_float_of_bytes(data, first + ivec2(4, 0)),
              stochtex_float_of_bytes(data, first + ivec2(6, 0)));
}

// Every texelFetch of the library reads one level of a float image.
#define texelFetch(data, texel, level) stochtex_texel_of_bytes(data, texel)
