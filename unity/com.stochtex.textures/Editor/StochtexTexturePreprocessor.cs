// Imports the data files of a stochtex export (a folder with its manifest.json) as data: no sRGB
// decoding, no compression, no resizing, no mip-maps, readable, in a format that keeps every
// value (RGBA Float for OpenEXR, RGBA64 for 16-bit PNG, RGBA32 for 8-bit PNG). The importer
// (StochtexImporter) reads these and makes the textures the shader samples, with the filter, wrap
// and mip-maps the manifest gives.

using System.IO;
using UnityEditor;
using UnityEngine;

namespace Stochtex.Editor
{
    public sealed class StochtexTexturePreprocessor : AssetPostprocessor
    {
        void OnPreprocessTexture()
        {
            StochtexManifest manifest = StochtexManifest.Beside(assetPath);
            StochtexTextureEntry entry = manifest == null ? null : manifest.Texture(Path.GetFileName(assetPath));
            if (entry != null)
                Configure((TextureImporter)assetImporter, entry);
        }

        public static void Configure(TextureImporter importer, StochtexTextureEntry entry)
        {
            importer.textureType = TextureImporterType.Default;
            importer.textureShape = TextureImporterShape.Texture2D;
            importer.sRGBTexture = false;
            importer.alphaSource = TextureImporterAlphaSource.FromInput;
            importer.alphaIsTransparency = false;
            importer.npotScale = TextureImporterNPOTScale.None;
            importer.mipmapEnabled = false;
            importer.isReadable = true;
            importer.filterMode = FilterMode.Point;
            importer.wrapMode = TextureWrapMode.Clamp;
            importer.textureCompression = TextureImporterCompression.Uncompressed;
            importer.maxTextureSize = 16384;
            TextureImporterPlatformSettings settings = importer.GetDefaultPlatformTextureSettings();
            settings.format = ImportFormat(entry.encoding);
            settings.textureCompression = TextureImporterCompression.Uncompressed;
            settings.maxTextureSize = 16384;
            importer.SetPlatformTextureSettings(settings);
        }

        static TextureImporterFormat ImportFormat(string encoding)
        {
            switch (encoding)
            {
                case "exr_float32":
                    return TextureImporterFormat.RGBAFloat;
                case "png16":
                    return TextureImporterFormat.RGBA64;
                case "png8":
                    return TextureImporterFormat.RGBA32;
            }
            throw new InvalidDataException("unknown encoding " + encoding + " in a stochtex manifest");
        }
    }
}
