// Stubs of the UnityEditor API that unity/com.stochtex.textures uses, with Unity 2021.3's
// signatures (see UnityEngine.cs). Compiled, never run.

using System;
using UnityEngine;
using Object = UnityEngine.Object;

namespace UnityEditor
{
    public class AssetImporter : Object
    {
        public static AssetImporter GetAtPath(string path) { throw new NotImplementedException(); }
        public void SaveAndReimport() { throw new NotImplementedException(); }
    }

    public class AssetPostprocessor
    {
        public string assetPath { get { throw new NotImplementedException(); } set { } }
        public AssetImporter assetImporter { get { throw new NotImplementedException(); } }
    }

    public enum TextureImporterType
    {
        Default = 0,
    }

    public enum TextureImporterShape
    {
        Texture2D = 1,
    }

    public enum TextureImporterAlphaSource
    {
        None = 0,
        FromInput = 1,
    }

    public enum TextureImporterNPOTScale
    {
        None = 0,
    }

    public enum TextureImporterCompression
    {
        Uncompressed = 0,
    }

    public enum TextureImporterFormat
    {
        RGBA32 = 4,
        RGBAFloat = 20,
        RGBA64 = 74,
    }

    public sealed class TextureImporterPlatformSettings
    {
        public TextureImporterFormat format { get; set; }
        public TextureImporterCompression textureCompression { get; set; }
        public int maxTextureSize { get; set; }
    }

    public sealed class TextureImporter : AssetImporter
    {
        public TextureImporterType textureType { get; set; }
        public TextureImporterShape textureShape { get; set; }
        public bool sRGBTexture { get; set; }
        public TextureImporterAlphaSource alphaSource { get; set; }
        public bool alphaIsTransparency { get; set; }
        public TextureImporterNPOTScale npotScale { get; set; }
        public bool mipmapEnabled { get; set; }
        public bool isReadable { get; set; }
        public FilterMode filterMode { get; set; }
        public TextureWrapMode wrapMode { get; set; }
        public TextureImporterCompression textureCompression { get; set; }
        public int maxTextureSize { get; set; }
        public TextureImporterPlatformSettings GetDefaultPlatformTextureSettings() { throw new NotImplementedException(); }
        public void SetPlatformTextureSettings(TextureImporterPlatformSettings platformSettings) { throw new NotImplementedException(); }
    }

    [AttributeUsage(AttributeTargets.Method, AllowMultiple = true)]
    public sealed class MenuItem : Attribute
    {
        public MenuItem(string itemName, bool isValidateFunction, int priority) { }
        public MenuItem(string itemName, bool isValidateFunction) { }
        public MenuItem(string itemName) { }
    }

    public static class Selection
    {
        public static Object activeObject { get { throw new NotImplementedException(); } set { } }
    }

    public enum ImportAssetOptions
    {
        Default = 0,
    }

    public static class AssetDatabase
    {
        public static string GetAssetPath(Object assetObject) { throw new NotImplementedException(); }
        public static bool IsValidFolder(string path) { throw new NotImplementedException(); }
        public static T LoadAssetAtPath<T>(string assetPath) where T : Object { throw new NotImplementedException(); }
        public static void CreateAsset(Object asset, string path) { throw new NotImplementedException(); }
        public static bool DeleteAsset(string path) { throw new NotImplementedException(); }
        public static void ImportAsset(string path, ImportAssetOptions options = ImportAssetOptions.Default) { throw new NotImplementedException(); }
        public static void SaveAssets() { throw new NotImplementedException(); }
    }

    public static class EditorUtility
    {
        public static void CopySerialized(Object source, Object dest) { throw new NotImplementedException(); }
    }
}
