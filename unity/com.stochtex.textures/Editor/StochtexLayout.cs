// A data file's texels as the export's shader reads them, from the pixels Unity's texture
// importer gives: the importer stores an image's last row first (GetPixels' row 0 is the
// bottom), where the shader reads the file's first row as texel row 0 (Load(int3(x, 0, 0)),
// v = 0: the first row of the texture's data in Direct3D, OpenGL, Vulkan and Metal alike).

using System;
using UnityEngine;

namespace Stochtex.Editor
{
    public static class StochtexLayout
    {
        // RGBA values, 4 a texel, the file's rows in order; a file of `channels` < 4 reads as an
        // R, RG or RGB texture does in OpenGL (missing colour 0, alpha 1), a grey + alpha file's
        // alpha in green. Those rows in order are also a 3-D texture's texels in x, y, z order,
        // its slices stacked top to bottom.
        public static float[] FileOrder(Color[] imported, int width, int height, int channels)
        {
            if (imported.Length != width * height)
                throw new ArgumentException("FileOrder: " + imported.Length + " pixels for " + width + " x " + height);
            var values = new float[width * height * 4];
            for (int row = 0; row < height; ++row)
                for (int x = 0; x < width; ++x)
                {
                    Color c = imported[(height - 1 - row) * width + x];
                    int at = (row * width + x) * 4;
                    values[at] = c.r;
                    values[at + 1] = channels == 2 ? c.a : (channels > 2 ? c.g : 0f);
                    values[at + 2] = channels > 2 ? c.b : 0f;
                    values[at + 3] = channels == 4 ? c.a : 1f;
                }
            return values;
        }

        // 16-bit samples (TextureFormat.RGBA64) of values k / 65535 (a 16-bit PNG's).
        public static ushort[] Unorm16(float[] values)
        {
            var samples = new ushort[values.Length];
            for (int i = 0; i < values.Length; ++i)
                samples[i] = (ushort)Math.Round(Math.Min(Math.Max(values[i], 0f), 1f) * 65535.0);
            return samples;
        }

        // Bytes (TextureFormat.RGBA32) of values k / 255 (an 8-bit PNG's).
        public static byte[] Unorm8(float[] values)
        {
            var bytes = new byte[values.Length];
            for (int i = 0; i < values.Length; ++i)
                bytes[i] = (byte)Math.Round(Math.Min(Math.Max(values[i], 0f), 1f) * 255.0);
            return bytes;
        }
    }
}
