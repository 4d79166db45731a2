// Binds a texture set to its renderer's materials through a MaterialPropertyBlock, in the editor
// and in play: what a Shader Graph material needs, whose graph declares no property for the
// export's textures (the export's HLSL declares them).

using UnityEngine;

namespace Stochtex
{
    [ExecuteAlways]
    [RequireComponent(typeof(Renderer))]
    public sealed class StochtexTextures : MonoBehaviour
    {
        public StochtexTextureSet textureSet;

        MaterialPropertyBlock block;

        void OnEnable()
        {
            Apply();
        }

        void OnValidate()
        {
            Apply();
        }

        public void Apply()
        {
            if (textureSet == null)
                return;
            Renderer target = GetComponent<Renderer>();
            if (block == null)
                block = new MaterialPropertyBlock();
            target.GetPropertyBlock(block);
            textureSet.SetOn(block);
            target.SetPropertyBlock(block);
        }
    }
}
