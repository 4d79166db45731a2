// The manifest.json of a `stochtex export-shader` folder (docs/shaders.md, "The manifest"), read
// with JsonUtility: the fields are its keys.

using System;
using System.IO;
using UnityEngine;

namespace Stochtex.Editor
{
    [Serializable]
    public sealed class StochtexOutput
    {
        public string name;     // colour, or a material's map
        public int components;  // 4 (colour), 3 (a colour or normal map) or 1
        public string kind;     // a material map's kind: colour, normal, height, ...
        public string colour;   // linear (linear light, an srgb model's) or data (as analysed)
    }

    [Serializable]
    public sealed class StochtexTextureEntry
    {
        public string uniform;   // stochtex_<name>, the texture the shader reads
        public string file;      // <name>.exr or <name>.png in the export folder
        public string encoding;  // exr_float32, png8 or png16
        public int channels;     // the file's: 1 grey, 2 grey + alpha, 3 RGB, 4 RGBA
        public int width;
        public int height;       // of one slice
        public int depth;        // 1: 2-D; more: 3-D, its slices stacked top to bottom in the file
        public string filter;    // nearest, linear or mipmap
        public string wrap;      // clamp_to_edge, clamp_to_border or repeat
        public int mip_levels;   // 1: none; more: generated from the file, 2 x 2 box
        public int anisotropy;   // 16 for mipmap, else 1
    }

    [Serializable]
    public sealed class StochtexManifest
    {
        public const string FileName = "manifest.json";

        public string format;
        public int version;
        public string method;
        public string variant;
        public string language;
        public string entry;
        public string shader;
        public string shader_graph;
        public StochtexOutput[] outputs;
        public StochtexTextureEntry[] textures;

        // The manifest of the export folder `folder`; one sentence where it is none.
        public static StochtexManifest Read(string folder)
        {
            string path = Path.Combine(folder, FileName);
            StochtexManifest manifest = JsonUtility.FromJson<StochtexManifest>(File.ReadAllText(path));
            if (manifest == null || manifest.format != "stochtex-shader-export" || manifest.version != 1)
                throw new InvalidDataException(path + " is not the manifest of a `stochtex export-shader` folder (version 1)");
            if (manifest.language != "hlsl")
                throw new InvalidDataException(folder + " holds a " + manifest.language + " export; Unity reads `stochtex export-shader --language hlsl`");
            return manifest;
        }

        // The manifest of the export holding the asset at `assetPath`, or null.
        public static StochtexManifest Beside(string assetPath)
        {
            string folder = Path.GetDirectoryName(assetPath);
            if (!File.Exists(Path.Combine(folder, FileName)))
                return null;
            try
            {
                return Read(folder);
            }
            catch (Exception e) when (e is InvalidDataException || e is ArgumentException)
            {
                return null;  // another manifest.json, or another language's export
            }
        }

        // The entry of the data file `fileName`, or null.
        public StochtexTextureEntry Texture(string fileName)
        {
            foreach (StochtexTextureEntry texture in textures)
                if (texture.file == fileName)
                    return texture;
            return null;
        }
    }
}
