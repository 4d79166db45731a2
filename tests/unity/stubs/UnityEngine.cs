// Stubs of the UnityEngine API that unity/com.stochtex.textures uses, with Unity 2021.3's
// signatures, so that its C# compiles here (mcs) as it would in Unity. Nothing here renders:
// bodies throw, except Color and JsonUtility, which the package test (unity_package_test.py)
// runs. Add what the package starts to use, as Unity declares it.

using System;
using System.Collections.Generic;
using System.Globalization;
using System.Reflection;
using System.Text;

namespace UnityEngine
{
    public class Object
    {
        public string name { get; set; }
    }

    public class ScriptableObject : Object
    {
        public static T CreateInstance<T>() where T : ScriptableObject { throw new NotImplementedException(); }
    }

    public class Component : Object
    {
        public T GetComponent<T>() { throw new NotImplementedException(); }
    }

    public class Behaviour : Component
    {
    }

    public class MonoBehaviour : Behaviour
    {
    }

    public class Renderer : Component
    {
        public void GetPropertyBlock(MaterialPropertyBlock properties) { throw new NotImplementedException(); }
        public void SetPropertyBlock(MaterialPropertyBlock properties) { throw new NotImplementedException(); }
    }

    public sealed class MaterialPropertyBlock
    {
        public void SetTexture(string name, Texture value) { throw new NotImplementedException(); }
    }

    public class Shader : Object
    {
    }

    public class Material : Object
    {
        public Material(Shader shader) { throw new NotImplementedException(); }
        public void SetTexture(string name, Texture value) { throw new NotImplementedException(); }
    }

    public enum TextureFormat
    {
        RGBA32 = 4,
        RGBAFloat = 20,
        RGBA64 = 74,
    }

    public enum FilterMode
    {
        Point = 0,
        Bilinear = 1,
        Trilinear = 2,
    }

    public enum TextureWrapMode
    {
        Repeat = 0,
        Clamp = 1,
        Mirror = 2,
        MirrorOnce = 3,
    }

    public class Texture : Object
    {
        public FilterMode filterMode { get; set; }
        public TextureWrapMode wrapMode { get; set; }
        public int anisoLevel { get; set; }
        public virtual int width { get { throw new NotImplementedException(); } set { } }
        public virtual int height { get { throw new NotImplementedException(); } set { } }
    }

    public sealed class Texture2D : Texture
    {
        public Texture2D(int width, int height, TextureFormat textureFormat, int mipCount, bool linear) { throw new NotImplementedException(); }
        public Color[] GetPixels() { throw new NotImplementedException(); }
        public void SetPixelData<T>(T[] data, int mipLevel, int sourceDataStartIndex = 0) { throw new NotImplementedException(); }
        public void Apply(bool updateMipmaps, bool makeNoLongerReadable) { throw new NotImplementedException(); }
    }

    public sealed class Texture3D : Texture
    {
        public Texture3D(int width, int height, int depth, TextureFormat textureFormat, int mipCount) { throw new NotImplementedException(); }
        public void SetPixelData<T>(T[] data, int mipLevel, int sourceDataStartIndex = 0) { throw new NotImplementedException(); }
        public void Apply(bool updateMipmaps, bool makeNoLongerReadable) { throw new NotImplementedException(); }
    }

    public struct Color
    {
        public float r;
        public float g;
        public float b;
        public float a;

        public Color(float r, float g, float b, float a)
        {
            this.r = r;
            this.g = g;
            this.b = b;
            this.a = a;
        }
    }

    public static class Debug
    {
        public static void Log(object message) { Console.WriteLine(message); }
    }

    [AttributeUsage(AttributeTargets.Class)]
    public sealed class ExecuteAlways : Attribute
    {
    }

    [AttributeUsage(AttributeTargets.Class, AllowMultiple = true)]
    public sealed class RequireComponent : Attribute
    {
        public RequireComponent(Type requiredComponent) { }
    }

    // JsonUtility.FromJson as Unity reads a [Serializable] class: public fields by name, a key
    // without a field ignored, a field without a key left as it was. Objects, arrays of
    // objects, strings and integers: what stochtex's manifest.json holds. The package test
    // reads which keys had a field ("Type.key") and which had none.
    public static class JsonUtility
    {
        public static readonly HashSet<string> ReadKeys = new HashSet<string>();
        public static readonly List<string> UnknownKeys = new List<string>();

        public static T FromJson<T>(string json)
        {
            int at = 0;
            return (T)Read(json, ref at, typeof(T));
        }

        static void Space(string json, ref int at)
        {
            while (at < json.Length && char.IsWhiteSpace(json[at]))
                ++at;
        }

        static object Read(string json, ref int at, Type type)
        {
            Space(json, ref at);
            char c = json[at];
            if (c == '{')
            {
                object value = Activator.CreateInstance(type);
                ++at;
                for (Space(json, ref at); json[at] != '}'; Space(json, ref at))
                {
                    if (json[at] == ',')
                    {
                        ++at;
                        continue;
                    }
                    string key = (string)Read(json, ref at, typeof(string));
                    Space(json, ref at);
                    ++at;  // ':'
                    FieldInfo field = type.GetField(key, BindingFlags.Public | BindingFlags.Instance);
                    (field == null ? (ICollection<string>)UnknownKeys : ReadKeys).Add(type.Name + "." + key);
                    object item = Read(json, ref at, field == null ? typeof(object) : field.FieldType);
                    if (field != null)
                        field.SetValue(value, item);
                }
                ++at;
                return value;
            }
            if (c == '[')
            {
                Type element = type.IsArray ? type.GetElementType() : typeof(object);
                var items = new List<object>();
                ++at;
                for (Space(json, ref at); json[at] != ']'; Space(json, ref at))
                {
                    if (json[at] == ',')
                        ++at;
                    else
                        items.Add(Read(json, ref at, element));
                }
                ++at;
                Array array = Array.CreateInstance(element, items.Count);
                for (int i = 0; i < items.Count; ++i)
                    array.SetValue(items[i], i);
                return array;
            }
            if (c == '"')
            {
                var text = new StringBuilder();
                for (++at; json[at] != '"'; ++at)
                    text.Append(json[at] == '\\' ? json[++at] : json[at]);
                ++at;
                return text.ToString();
            }
            int start = at;
            while (at < json.Length && "+-.0123456789eEtrufalsn".IndexOf(json[at]) >= 0)
                ++at;
            string number = json.Substring(start, at - start);
            return type == typeof(int) ? (object)int.Parse(number, CultureInfo.InvariantCulture) : number;
        }
    }
}
