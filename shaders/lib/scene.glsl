// What the GPU scene gives shaders (passes/gpu_scene.h fills it): the camera, per-draw push
// constants and the lights. A shader that declares a `Camera` uniform block or a `Lights`
// storage block is bound to the scene's, whatever its pass declares.
#ifndef RG_SCENE_GLSL
#define RG_SCENE_GLSL

#ifndef RG_CAMERA_SET
#define RG_CAMERA_SET 0
#endif
#ifndef RG_CAMERA_BINDING
#define RG_CAMERA_BINDING 15
#endif
#ifndef RG_LIGHTS_BINDING
#define RG_LIGHTS_BINDING 14
#endif

layout(set = RG_CAMERA_SET, binding = RG_CAMERA_BINDING) uniform Camera {
    mat4 viewProj;
    mat4 view;
    mat4 proj;
    mat4 invViewProj;
    vec4 position;   // xyz: world position (metres)
    vec4 viewport;   // width, height, 1/width, 1/height
} camera;

// World position of a pixel from its depth (Vulkan depth range 0..1).
vec3 rgWorldPosition(vec2 uv, float depth) {
    vec4 clip = vec4(uv * 2.0 - 1.0, depth, 1.0);
    vec4 world = camera.invViewProj * clip;
    return world.xyz / world.w;
}

// Light types, as graph/scene's LightType.
#define RG_LIGHT_POINT 0
#define RG_LIGHT_SPOT 1
#define RG_LIGHT_SUN 2

struct RgLight {
    vec4 positionType;     // xyz position (m), w type
    vec4 directionRadius;  // xyz direction the light travels, w: 1/range² (0 = no range)
    vec4 intensity;        // rgb: colour × luminous intensity (cd) for punctual lights, × illuminance (lux) for the sun
    vec4 params;           // spot: angle scale, angle offset (lst:4); sun: angular radius (rad)
};

layout(set = RG_CAMERA_SET, binding = RG_LIGHTS_BINDING, std430) readonly buffer Lights {
    uvec4 count;  // x: number of lights
    RgLight light[];
} lights;

#endif
