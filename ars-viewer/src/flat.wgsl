// ARS's fast material: Lambert shading with a headlight and a key light from above,
// a little Blinn-Phong highlight, and an optional checker pattern (floors). Cheap
// enough for Mesa's software rasteriser.

struct Frame {
    view: mat4x4<f32>,
    proj: mat4x4<f32>,
    // The camera's position (xyz).
    eye: vec4<f32>,
    // Unit direction towards the key light (xyz).
    key: vec4<f32>,
}

@group(0) @binding(0)
var<uniform> frame: Frame;

struct Object {
    transform: mat4x4<f32>,
    scale: mat3x3<f32>,
    color: vec4<f32>,
    // x: 1 for a checker pattern; y: its cell size (m).
    pattern: vec4<f32>,
}

@group(1) @binding(0)
var<uniform> object: Object;

struct VertexInput {
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
}

struct VertexOutput {
    @builtin(position) clip: vec4<f32>,
    @location(0) world: vec3<f32>,
    @location(1) normal: vec3<f32>,
}

@vertex
fn vs_main(v: VertexInput) -> VertexOutput {
    var out: VertexOutput;
    let world = object.transform * vec4<f32>(object.scale * v.position, 1.0);
    out.clip = frame.proj * frame.view * world;
    out.world = world.xyz;
    // Normals scale by the inverse of the (diagonal) scale.
    let s = vec3<f32>(object.scale[0][0], object.scale[1][1], object.scale[2][2]);
    out.normal = (object.transform * vec4<f32>(v.normal / s, 0.0)).xyz;
    return out;
}

@fragment
fn fs_main(in: VertexOutput, @builtin(front_facing) front: bool) -> @location(0) vec4<f32> {
    var n = normalize(in.normal);
    if (!front) {
        n = -n;
    }
    let to_eye = normalize(frame.eye.xyz - in.world);
    let head = max(dot(n, to_eye), 0.0);
    let key = max(dot(n, frame.key.xyz), 0.0);
    var base = object.color.rgb;
    if (object.pattern.x > 0.5) {
        let cell = floor(in.world.x / object.pattern.y) + floor(in.world.z / object.pattern.y);
        if (cell - 2.0 * floor(cell / 2.0) > 0.5) {
            base = base * 0.82;
        }
    }
    let halfway = normalize(to_eye + frame.key.xyz);
    let shine = pow(max(dot(n, halfway), 0.0), 48.0) * 0.15;
    let lit = base * (0.30 + 0.45 * head + 0.35 * key) + vec3<f32>(shine);
    return vec4<f32>(lit, object.color.a);
}
