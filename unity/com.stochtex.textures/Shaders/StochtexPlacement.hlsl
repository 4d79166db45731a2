// The placement of a stochtex export on a mesh, and the sRGB transfer functions, for Shader Graph
// Custom Function nodes (Type File, this file, precision Float) and for shaders that include it
// (the importer's example shader does). Fragment stage only (ddx, ddy).
#ifndef STOCHTEX_PLACEMENT_INCLUDED
#define STOCHTEX_PLACEMENT_INCLUDED

// Name StochtexPlacement: the exemplar point p = origin + (u, 1 - v) * size of the mesh's uv, in
// exemplar pixels (v = 1, the top of a Unity texture, is the exemplar's first row), and its
// screen derivatives, the footprint the exported function filters over. A mesh whose uv span
// [0, 1] over W x H screen pixels shows `stochtex render --size WxH --origin X,Y --scale S` for
// origin (X, Y) and size (W * S, H * S).
void StochtexPlacement_float(float2 uv, float2 origin, float2 size, out float2 p, out float2 dpdx,
                             out float2 dpdy)
{
    p = origin + float2(uv.x, 1.0 - uv.y) * size;
    dpdx = ddx(p);
    dpdy = ddy(p);
}

float3 stochtex_srgb_decode(float3 encoded)
{
    float3 low = encoded / 12.92;
    float3 high = pow(max((encoded + 0.055) / 1.055, 0.0), 2.4);
    return float3(encoded.r <= 0.04045 ? low.r : high.r, encoded.g <= 0.04045 ? low.g : high.g,
                  encoded.b <= 0.04045 ? low.b : high.b);
}

float3 stochtex_srgb_encode(float3 light)
{
    float3 low = light * 12.92;
    float3 high = 1.055 * pow(max(light, 0.0), 1.0 / 2.4) - 0.055;
    return float3(light.r <= 0.0031308 ? low.r : high.r, light.g <= 0.0031308 ? low.g : high.g,
                  light.b <= 0.0031308 ? low.b : high.b);
}

// Name StochtexSrgbDecode: sRGB-encoded values (a data export of an sRGB photo) to linear light,
// which a Lit material's Base Color takes in a Linear colour space project.
void StochtexSrgbDecode_float(float3 encoded, out float3 decoded)
{
    decoded = stochtex_srgb_decode(encoded);
}

// Name StochtexSrgbEncode: linear light (an srgb export's colour) to sRGB-encoded values, for an
// Unlit output in a Gamma colour space project.
void StochtexSrgbEncode_float(float3 light, out float3 encoded)
{
    encoded = stochtex_srgb_encode(light);
}

#endif  // STOCHTEX_PLACEMENT_INCLUDED
