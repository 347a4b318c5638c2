// SPDX-License-Identifier: MIT
// emcv_adaptive_language.hlsl — installed with the HLSL modules (share/emcv/module/hlsl): the HLSL side of
// module/emcv_adaptive_language.glsl. The modules' code is GLSL written in the subset HLSL shares
// (docs/porting.md, "HLSL modules"); this file gives HLSL the GLSL names that code uses (types, built-ins, the
// invocation's index), and the macros through which the two languages differ. The generated modules include it;
// an application includes the modules, after emcv_port.hlsl, and calls emcv_hlsl_set_invocation first in each
// entry point that runs a module's function.
#ifndef EMCV_ADAPTIVE_LANGUAGE_H
#define EMCV_ADAPTIVE_LANGUAGE_H

#ifndef EMCV_PORT_HLSL
#error "emcv_adaptive_language.hlsl: #include \"emcv_port.hlsl\" (share/emcv) before the HLSL modules"
#endif

// The modules' macros (module/emcv_adaptive_language.glsl says why each exists).
#define EMCV_STATIC static
#define EMCV_ATOMIC_ADD(dest, value) InterlockedAdd(dest, value)
#define EMCV_ATOMIC_EXCHANGE(dest, value, original) InterlockedExchange(dest, value, original)
// The port's GLSL spells it `precise` too; emcv_port.hlsl, translated code, does not define the macro.
#ifndef EMCV_PRECISE
#define EMCV_PRECISE precise
#endif

// GLSL's vector types.
typedef float2 vec2;
typedef float3 vec3;
typedef float4 vec4;
typedef int2 ivec2;
typedef int3 ivec3;
typedef int4 ivec4;
typedef uint2 uvec2;
typedef uint3 uvec3;
typedef uint4 uvec4;

// GLSL's built-ins that HLSL names otherwise (vector comparisons: HLSL's operators, componentwise).
uint floatBitsToUint(float x) { return asuint(x); }
float uintBitsToFloat(uint x) { return asfloat(x); }
bool2 equal(float2 a, float2 b) { return a == b; }
bool2 equal(int2 a, int2 b) { return a == b; }
bool2 notEqual(float2 a, float2 b) { return a != b; }
bool2 notEqual(int2 a, int2 b) { return a != b; }
bool2 lessThan(float2 a, float2 b) { return a < b; }
bool2 lessThan(int2 a, int2 b) { return a < b; }
bool2 greaterThanEqual(float2 a, float2 b) { return a >= b; }
bool2 greaterThanEqual(int2 a, int2 b) { return a >= b; }

// Workgroup memory and its barriers: GLSL's barrier() also orders shared memory, as this one does.
#define shared groupshared
#define barrier() GroupMemoryBarrierWithGroupSync()
#define memoryBarrierShared() GroupMemoryBarrier()

// The invocation's place in its workgroup (GLSL's gl_LocalInvocationID and gl_LocalInvocationIndex), which HLSL
// hands only to the entry point (SV_GroupThreadID, SV_GroupIndex): the entry point stores them here first.
static uint3 emcv_hlsl_local_invocation_id;
static uint emcv_hlsl_local_invocation_index;
#define gl_LocalInvocationID emcv_hlsl_local_invocation_id
#define gl_LocalInvocationIndex emcv_hlsl_local_invocation_index

/// Call first in an entry point that runs a module's function, with its SV_GroupThreadID and SV_GroupIndex.
void emcv_hlsl_set_invocation(uint3 group_thread_id, uint group_index) {
    emcv_hlsl_local_invocation_id = group_thread_id;
    emcv_hlsl_local_invocation_index = group_index;
}

#endif  // #ifndef EMCV_ADAPTIVE_LANGUAGE_H
