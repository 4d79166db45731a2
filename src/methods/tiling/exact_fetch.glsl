// The four texels around (x, y) of a level (fetch_bilinear): the rows' and columns' first
// indices in the model's array, periodic, and the bilinear fractions.
struct TilingTaps {
  int r0;
  int r1;
  int x0;
  int x1;
  float tu;
  float tv;
};

TilingTaps tiling_taps(int level, float x, float y) {
  int width = TILING_LEVEL_WIDTH[level];
  int height = TILING_LEVEL_HEIGHT[level];
  float u = x * (float(width) / float(TILING_WIDTH)) - 0.5;
  float v = y * (float(height) / float(TILING_HEIGHT)) - 0.5;
  float cell_u = floor(u);
  float cell_v = floor(v);
  TilingTaps taps;
  taps.tu = u - cell_u;
  taps.tv = v - cell_v;
  int x0 = int(cell_u - float(width) * floor(cell_u / float(width)));
  int y0 = int(cell_v - float(height) * floor(cell_v / float(height)));
  if (x0 >= width) x0 -= width;
  if (y0 >= height) y0 -= height;
  if (x0 < 0) x0 += width;
  if (y0 < 0) y0 += height;
  int y1 = y0 + 1 == height ? 0 : y0 + 1;
  int base = TILING_LEVEL_TEXELS[level];
  taps.r0 = base + y0 * width * TILING_CHANNELS;
  taps.r1 = base + y1 * width * TILING_CHANNELS;
  taps.x0 = x0 * TILING_CHANNELS;
  taps.x1 = (x0 + 1 == width ? 0 : x0 + 1) * TILING_CHANNELS;
  return taps;
}

// Adds weight * the bilinear value of channel c at the taps to `value`.
void tiling_add_tap_value(TilingTaps t, float weight, int c, inout float value) {
  value += weight * (1.0 - t.tu) * (1.0 - t.tv) * tiling_data_at(t.r0 + t.x0 + c) +
           weight * t.tu * (1.0 - t.tv) * tiling_data_at(t.r0 + t.x1 + c) +
           weight * (1.0 - t.tu) * t.tv * tiling_data_at(t.r1 + t.x0 + c) +
           weight * t.tu * t.tv * tiling_data_at(t.r1 + t.x1 + c);
}
