// Adds weight * level(x, y), bilinear and periodic (fetch_bilinear).
void tiling_fetch(int level, float x, float y, float weight, inout vec4 acc) {
  int width = TILING_LEVEL_WIDTH[level];
  int height = TILING_LEVEL_HEIGHT[level];
  float u = x * (float(width) / float(TILING_WIDTH)) - 0.5;
  float v = y * (float(height) / float(TILING_HEIGHT)) - 0.5;
  float cell_u = floor(u);
  float cell_v = floor(v);
  float tu = u - cell_u;
  float tv = v - cell_v;
  int x0 = int(cell_u - float(width) * floor(cell_u / float(width)));
  int y0 = int(cell_v - float(height) * floor(cell_v / float(height)));
  if (x0 >= width) x0 -= width;
  if (y0 >= height) y0 -= height;
  if (x0 < 0) x0 += width;
  if (y0 < 0) y0 += height;
  int x1 = x0 + 1 == width ? 0 : x0 + 1;
  int y1 = y0 + 1 == height ? 0 : y0 + 1;
  int base = TILING_LEVEL_TEXELS[level];
  int r0 = base + y0 * width * TILING_CHANNELS;
  int r1 = base + y1 * width * TILING_CHANNELS;
  for (int c = 0; c < TILING_CHANNELS; ++c)
    acc[c] += weight * (1.0 - tu) * (1.0 - tv) * tiling_data_at(r0 + x0 * TILING_CHANNELS + c) +
              weight * tu * (1.0 - tv) * tiling_data_at(r0 + x1 * TILING_CHANNELS + c) +
              weight * (1.0 - tu) * tv * tiling_data_at(r1 + x0 * TILING_CHANNELS + c) +
              weight * tu * tv * tiling_data_at(r1 + x1 * TILING_CHANNELS + c);
}

