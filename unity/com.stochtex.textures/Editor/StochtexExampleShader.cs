// The text of an export's example shader: an unlit pass (Built-in Render Pipeline; URP draws it
// as an unlit pass) showing the export's colour, or a material's first colour map, on a mesh's uv
// through the package's Shaders/StochtexExample.hlsl. The export's texture properties are
// declared, so that a material keeps them.

using System.Text;

namespace Stochtex.Editor
{
    public static class StochtexExampleShader
    {
        public static string Text(StochtexManifest manifest, string shaderName)
        {
            StochtexOutput shown = Shown(manifest.outputs);
            string call = manifest.entry + "(p, dpdx, dpdy, seed)";
            string value = manifest.outputs.Length == 1 && shown.name == "colour"
                               ? call + ".rgb"
                               : "(" + call + "." + shown.name + ")" + (shown.components == 1 ? ".xxx" : "");
            bool linearLight = shown.colour == "linear";
            var text = new StringBuilder();
            text.Append("// Written by the com.stochtex.textures importer from manifest.json: ")
                .Append(manifest.method).Append(" (").Append(manifest.variant).Append("), showing ")
                .Append(shown.name).Append(" (").Append(shown.colour).Append(").\n")
                .Append("Shader \"").Append(shaderName).Append("\"\n{\n    Properties\n    {\n")
                .Append("        _StochtexOrigin (\"Origin (exemplar pixels)\", Vector) = (0, 0, 0, 0)\n")
                .Append("        _StochtexSize (\"Size of uv [0, 1] (exemplar pixels)\", Vector) = (512, 512, 0, 0)\n")
                .Append("        _StochtexSeed (\"Seed (a whole number below 2^24)\", Float) = 7\n");
            if (!linearLight)
                text.Append("        [Toggle] _StochtexDecode (\"Decode sRGB (a photo analysed as data)\", Float) = 0\n");
            foreach (StochtexTextureEntry texture in manifest.textures)
                text.Append("        [NoScaleOffset] ").Append(texture.uniform).Append(" (\"")
                    .Append(texture.file).Append("\", ").Append(texture.depth == 1 ? "2D" : "3D")
                    .Append(texture.depth == 1 ? ") = \"black\" {}\n" : ") = \"\" {}\n");
            text.Append("    }\n    SubShader\n    {\n        Tags { \"RenderType\" = \"Opaque\" }\n")
                .Append("        Pass\n        {\n            CGPROGRAM\n")
                .Append("            #pragma vertex stochtex_example_vertex\n")
                .Append("            #pragma fragment stochtex_example_fragment\n")
                .Append("            #pragma target 3.5\n")
                .Append("            #include \"UnityCG.cginc\"\n")
                .Append("            #include \"").Append(manifest.shader_graph).Append("\"\n")
                .Append("            #define STOCHTEX_EXAMPLE_VALUE(p, dpdx, dpdy, seed) ").Append(value).Append("\n")
                .Append("            #define STOCHTEX_EXAMPLE_LINEAR_LIGHT ").Append(linearLight ? "1" : "0").Append("\n")
                .Append("            #include \"Packages/com.stochtex.textures/Shaders/StochtexExample.hlsl\"\n")
                .Append("            ENDCG\n        }\n    }\n}\n");
            return text.ToString();
        }

        // The output shown: the only one, or a material's first colour map of 3 components
        // (albedo), else its first map.
        static StochtexOutput Shown(StochtexOutput[] outputs)
        {
            foreach (StochtexOutput output in outputs)
                if (output.kind == "colour" && output.components == 3)
                    return output;
            return outputs[0];
        }
    }
}
