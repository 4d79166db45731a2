// The textures of one stochtex export, each under the name its shader reads it by
// (stochtex_<name>): made by the importer (Editor/StochtexImporter.cs), set on a material or a
// renderer's property block so that no script has to bind them by name.

using System;
using UnityEngine;

namespace Stochtex
{
    public sealed class StochtexTextureSet : ScriptableObject
    {
        [Serializable]
        public struct Binding
        {
            public string uniform;  // stochtex_<name>, the shader's texture
            public Texture texture;
        }

        public string method;   // the exporting method: texton, tiling, lrp, gabor, texton_mix
        public string entry;    // the function: stochtex_<method> or stochtex_<method>_material
        public string variant;  // exact or fast
        public Binding[] textures = new Binding[0];

        public void SetOn(Material material)
        {
            foreach (Binding binding in textures)
                material.SetTexture(binding.uniform, binding.texture);
        }

        public void SetOn(MaterialPropertyBlock block)
        {
            foreach (Binding binding in textures)
                block.SetTexture(binding.uniform, binding.texture);
        }
    }
}
