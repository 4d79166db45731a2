// The program of the importer's example shader (Editor/StochtexImporter.cs writes the .shader):
// an unlit pass showing an export on a mesh's uv. The .shader includes UnityCG.cginc, the export's
// Shader Graph file, defines
//   STOCHTEX_EXAMPLE_VALUE(p, dpdx, dpdy, seed)  the export's colour as a float3 (a material's:
//                                               one of its maps), and
//   STOCHTEX_EXAMPLE_LINEAR_LIGHT                1 where that is linear light (an srgb model's),
//                                               0 where it is data,
// and then includes this file.
#ifndef STOCHTEX_EXAMPLE_INCLUDED
#define STOCHTEX_EXAMPLE_INCLUDED

#include "StochtexPlacement.hlsl"

float4 _StochtexOrigin;
float4 _StochtexSize;
float _StochtexSeed;
float _StochtexDecode;

struct StochtexVertex
{
    float4 vertex : POSITION;
    float2 uv : TEXCOORD0;
};

struct StochtexFragment
{
    float4 position : SV_POSITION;
    float2 uv : TEXCOORD0;
};

StochtexFragment stochtex_example_vertex(StochtexVertex v)
{
    StochtexFragment f;
    f.position = UnityObjectToClipPos(v.vertex);
    f.uv = v.uv;
    return f;
}

float4 stochtex_example_fragment(StochtexFragment f) : SV_Target
{
    float2 p;
    float2 dpdx;
    float2 dpdy;
    StochtexPlacement_float(f.uv, _StochtexOrigin.xy, _StochtexSize.xy, p, dpdx, dpdy);
    float3 value = STOCHTEX_EXAMPLE_VALUE(p, dpdx, dpdy, (uint)_StochtexSeed);
#if !STOCHTEX_EXAMPLE_LINEAR_LIGHT
    // Data: shown as it is, or decoded where it is a photo's sRGB-encoded values.
    if (_StochtexDecode > 0.5)
        value = stochtex_srgb_decode(value);
#endif
#ifdef UNITY_COLORSPACE_GAMMA
    // A Gamma colour space project's framebuffer holds encoded values; a Linear one encodes itself.
    value = stochtex_srgb_encode(value);
#endif
    return float4(value, 1.0);
}

#endif  // STOCHTEX_EXAMPLE_INCLUDED
