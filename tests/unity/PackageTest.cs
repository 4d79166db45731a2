// The Unity package's C# that runs without Unity, run by mono against the stubs
// (unity_package_test.py): the layout of a data file's texels (rows, channels, 3-D slices), and
// the manifest.json of each export folder given, read into the package's classes (every key a
// field, every field a key of some manifest) and written out as its example shader, which the
// Python test then compiles. Exit status 1 on a failure, each named on stderr.

using System;
using System.Collections.Generic;
using System.IO;
using System.Reflection;
using Stochtex.Editor;
using UnityEngine;

static class PackageTest
{
    static int failures;

    static void Expect(bool ok, string what)
    {
        if (ok)
            return;
        Console.Error.WriteLine("FAIL: " + what);
        ++failures;
    }

    // A file of 2 x 4 pixels, pixel (x, row) of value (x + 10 row) / 100 in red, green and blue
    // offset by 0.001 and 0.002, alpha 0.5, as Unity's importer gives it: the last row first.
    static float Value(int x, int row)
    {
        return (x + 10 * row) / 100f;
    }

    static void Layout()
    {
        const int width = 2;
        const int rows = 4;
        var imported = new Color[width * rows];
        for (int row = 0; row < rows; ++row)
            for (int x = 0; x < width; ++x)
            {
                float v = Value(x, row);
                imported[(rows - 1 - row) * width + x] = new Color(v, v + 0.001f, v + 0.002f, 0.5f);
            }
        float[] rgba = StochtexLayout.FileOrder(imported, width, rows, 4);
        for (int row = 0; row < rows; ++row)
            for (int x = 0; x < width; ++x)
            {
                int at = (row * width + x) * 4;
                Expect(rgba[at] == Value(x, row) && rgba[at + 1] == Value(x, row) + 0.001f &&
                           rgba[at + 2] == Value(x, row) + 0.002f && rgba[at + 3] == 0.5f,
                       "RGBA texel (" + x + ", " + row + ") is the file's pixel");
            }
        // 3-D: slices of 2 x 2 stacked top to bottom; texel (x, y, z) at x + 2 y + 4 z.
        for (int z = 0; z < 2; ++z)
            for (int y = 0; y < 2; ++y)
                for (int x = 0; x < width; ++x)
                    Expect(rgba[(x + width * y + width * 2 * z) * 4] == Value(x, 2 * z + y),
                           "3-D texel (" + x + ", " + y + ", " + z + ") is the file's pixel (" + x + ", " + (2 * z + y) + ")");
        float[] grey = StochtexLayout.FileOrder(imported, width, rows, 1);
        Expect(grey[0] == Value(0, 0) && grey[1] == 0f && grey[2] == 0f && grey[3] == 1f,
               "a grey file reads (v, 0, 0, 1)");
        float[] greyAlpha = StochtexLayout.FileOrder(imported, width, rows, 2);
        Expect(greyAlpha[1] == 0.5f && greyAlpha[2] == 0f && greyAlpha[3] == 1f,
               "a grey + alpha file reads (v, alpha, 0, 1)");
        float[] rgb = StochtexLayout.FileOrder(imported, width, rows, 3);
        Expect(rgb[2] == Value(0, 0) + 0.002f && rgb[3] == 1f, "an RGB file reads alpha 1");
        ushort[] samples = StochtexLayout.Unorm16(new float[] { 0f, 1f / 65535f, 40000f / 65535f, 1f });
        Expect(samples[0] == 0 && samples[1] == 1 && samples[2] == 40000 && samples[3] == 65535,
               "16-bit samples come back as they were");
        byte[] bytes = StochtexLayout.Unorm8(new float[] { 0f, 1f / 255f, 200f / 255f, 1f });
        Expect(bytes[0] == 0 && bytes[1] == 1 && bytes[2] == 200 && bytes[3] == 255,
               "bytes come back as they were");
    }

    static int Main(string[] folders)
    {
        Layout();
        foreach (string folder in folders)
        {
            StochtexManifest manifest = StochtexManifest.Read(folder);
            foreach (StochtexTextureEntry texture in manifest.textures)
                Expect(File.Exists(Path.Combine(folder, texture.file)), folder + ": " + texture.file + " exists");
            Expect(File.Exists(Path.Combine(folder, manifest.shader_graph)), folder + ": " + manifest.shader_graph + " exists");
            string shader = StochtexExampleShader.Text(manifest, "Stochtex/test/" + manifest.method);
            File.WriteAllText(Path.Combine(folder, manifest.method + "_example.shader"), shader);
        }
        Expect(JsonUtility.UnknownKeys.Count == 0, "manifest keys without a field: " + string.Join(", ", JsonUtility.UnknownKeys));
        foreach (Type type in new[] { typeof(StochtexManifest), typeof(StochtexOutput), typeof(StochtexTextureEntry) })
            foreach (FieldInfo field in type.GetFields(BindingFlags.Public | BindingFlags.Instance))
                Expect(JsonUtility.ReadKeys.Contains(type.Name + "." + field.Name),
                       type.Name + "." + field.Name + " is no key of the manifests read");
        return failures == 0 ? 0 : 1;
    }
}
