//! The fast material: Lambert shading with a headlight and a key light, and a checker
//! pattern for floors (`flat.wgsl`). kiss3d's default physically based material is
//! costly per pixel on Mesa's software rasteriser; this one is cheap (the bench
//! `viewer_fps` measures the frame times).

use std::any::Any;
use std::cell::RefCell;
use std::rc::Rc;

use bytemuck::{Pod, Zeroable};
use kiss3d::camera::Camera3d;
use kiss3d::context::Context;
use kiss3d::glamx::{Mat3, Pose3, Vec3};
use kiss3d::light::LightCollection;
use kiss3d::resource::vertex_index::VERTEX_INDEX_FORMAT;
use kiss3d::resource::{
    DynamicUniformBuffer, GpuData, GpuMesh3d, Material3d, MaterialManager3d, PipelineCache, RenderContext,
    multisample_state,
};
use kiss3d::scene::{InstancesBuffer3d, ObjectData3d};

/// The material as kiss3d's scene nodes hold it.
pub(crate) type SharedMaterial = Rc<RefCell<Box<dyn Material3d + 'static>>>;

/// Per-frame uniforms: camera and key light.
#[repr(C)]
#[derive(Copy, Clone, Pod, Zeroable)]
struct FrameUniforms {
    view: [[f32; 4]; 4],
    proj: [[f32; 4]; 4],
    eye: [f32; 4],
    key: [f32; 4],
}

/// Per-object uniforms: pose, scale, colour, pattern.
#[repr(C)]
#[derive(Copy, Clone, Pod, Zeroable)]
struct ObjectUniforms {
    transform: [[f32; 4]; 4],
    /// A mat3x3 as WGSL lays it out in a uniform buffer: three padded columns.
    scale: [[f32; 4]; 3],
    color: [f32; 4],
    pattern: [f32; 4],
}

/// Where an object's uniforms are in this frame's buffer.
#[derive(Default)]
struct FlatGpuData {
    offset: Option<u32>,
}

impl GpuData for FlatGpuData {
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// Lambert shading in the object's colour, optionally checkered.
pub(crate) struct FlatMaterial {
    checker: Option<f32>,
    cull: PipelineCache,
    no_cull: PipelineCache,
    object_layout: wgpu::BindGroupLayout,
    frame_buffer: wgpu::Buffer,
    frame_group: wgpu::BindGroup,
    objects: DynamicUniformBuffer<ObjectUniforms>,
    object_group: wgpu::BindGroup,
    /// Whether this frame's uniforms were written.
    frame_written: bool,
}

/// The direction the key light comes from: above, a little to the side.
const KEY_LIGHT: [f32; 3] = [0.3, 1.0, 0.45];

impl FlatMaterial {
    /// The material of this thread (`checker`: the cell size of a checker pattern, m),
    /// registered with kiss3d's material manager, which starts and flushes its frames.
    pub(crate) fn shared(checker: Option<f32>) -> SharedMaterial {
        let name = match checker {
            Some(size) => format!("ars-flat-checker-{size}"),
            None => "ars-flat".to_string(),
        };
        MaterialManager3d::get_global_manager(|manager| {
            manager.get(&name).unwrap_or_else(|| {
                let material: SharedMaterial = Rc::new(RefCell::new(Box::new(FlatMaterial::new(checker))));
                manager.add(material.clone(), &name);
                material
            })
        })
    }

    fn new(checker: Option<f32>) -> Self {
        let ctxt = Context::get();
        let uniform_layout = |label, dynamic| {
            ctxt.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some(label),
                entries: &[wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Uniform,
                        has_dynamic_offset: dynamic,
                        min_binding_size: None,
                    },
                    count: None,
                }],
            })
        };
        let frame_layout = uniform_layout("ars_flat_frame_layout", false);
        let object_layout = uniform_layout("ars_flat_object_layout", true);
        let layout = ctxt.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("ars_flat_pipeline_layout"),
            bind_group_layouts: &[Some(&frame_layout), Some(&object_layout)],
            immediate_size: 0,
        });
        let shader = ctxt.create_shader_module(Some("ars_flat_shader"), include_str!("flat.wgsl"));
        let build = Rc::new(move |cull_mode: Option<wgpu::Face>, sample_count: u32| {
            flat_pipeline(&layout, &shader, cull_mode, sample_count)
        });
        let cull = PipelineCache::new({
            let build = build.clone();
            move |samples| build(Some(wgpu::Face::Back), samples)
        });
        let no_cull = PipelineCache::new(move |samples| build(None, samples));
        let frame_buffer = ctxt.create_buffer(&wgpu::BufferDescriptor {
            label: Some("ars_flat_frame_uniforms"),
            size: std::mem::size_of::<FrameUniforms>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let frame_group = ctxt.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ars_flat_frame_group"),
            layout: &frame_layout,
            entries: &[wgpu::BindGroupEntry { binding: 0, resource: frame_buffer.as_entire_binding() }],
        });
        let objects = DynamicUniformBuffer::<ObjectUniforms>::new("ars_flat_object_uniforms");
        let object_group = object_group(&object_layout, &objects);
        FlatMaterial {
            checker,
            cull,
            no_cull,
            object_layout,
            frame_buffer,
            frame_group,
            objects,
            object_group,
            frame_written: false,
        }
    }
}

/// The flat material's render pipeline: positions and normals in, one colour out,
/// depth-tested, with `cull_mode` and `sample_count` samples a pixel.
fn flat_pipeline(
    layout: &wgpu::PipelineLayout,
    shader: &wgpu::ShaderModule,
    cull_mode: Option<wgpu::Face>,
    sample_count: u32,
) -> wgpu::RenderPipeline {
    let vec3_buffer = |location| wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<[f32; 3]>() as wgpu::BufferAddress,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: if location == 0 { &POSITION } else { &NORMAL },
    };
    Context::get().create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some("ars_flat_pipeline"),
        layout: Some(layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some("vs_main"),
            buffers: &[Some(vec3_buffer(0)), Some(vec3_buffer(1))],
            compilation_options: Default::default(),
        },
        fragment: Some(wgpu::FragmentState {
            module: shader,
            entry_point: Some("fs_main"),
            targets: &[Some(wgpu::ColorTargetState {
                format: Context::render_format(),
                blend: Some(wgpu::BlendState::REPLACE),
                write_mask: wgpu::ColorWrites::ALL,
            })],
            compilation_options: Default::default(),
        }),
        primitive: wgpu::PrimitiveState {
            topology: wgpu::PrimitiveTopology::TriangleList,
            strip_index_format: None,
            front_face: wgpu::FrontFace::Ccw,
            cull_mode,
            polygon_mode: wgpu::PolygonMode::Fill,
            unclipped_depth: false,
            conservative: false,
        },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: Context::depth_format(),
            depth_write_enabled: Some(true),
            depth_compare: Some(wgpu::CompareFunction::Less),
            stencil: wgpu::StencilState::default(),
            bias: wgpu::DepthBiasState::default(),
        }),
        multisample: multisample_state(sample_count),
        multiview_mask: None,
        cache: None,
    })
}

const POSITION: [wgpu::VertexAttribute; 1] =
    [wgpu::VertexAttribute { offset: 0, shader_location: 0, format: wgpu::VertexFormat::Float32x3 }];
const NORMAL: [wgpu::VertexAttribute; 1] =
    [wgpu::VertexAttribute { offset: 0, shader_location: 1, format: wgpu::VertexFormat::Float32x3 }];

fn object_group(layout: &wgpu::BindGroupLayout, objects: &DynamicUniformBuffer<ObjectUniforms>) -> wgpu::BindGroup {
    Context::get().create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("ars_flat_object_group"),
        layout,
        entries: &[wgpu::BindGroupEntry {
            binding: 0,
            resource: wgpu::BindingResource::Buffer(wgpu::BufferBinding {
                buffer: objects.buffer(),
                offset: 0,
                size: std::num::NonZeroU64::new(objects.aligned_size()),
            }),
        }],
    })
}

impl Material3d for FlatMaterial {
    fn create_gpu_data(&self) -> Box<dyn GpuData> {
        Box::new(FlatGpuData::default())
    }

    fn begin_frame(&mut self) {
        self.objects.clear();
        self.frame_written = false;
    }

    fn flush(&mut self) {
        if self.objects.flush() {
            // The buffer grew: bind the new one.
            self.object_group = object_group(&self.object_layout, &self.objects);
        }
    }

    fn prepare(
        &mut self,
        pass: usize,
        transform: Pose3,
        scale: Vec3,
        camera: &mut dyn Camera3d,
        _lights: &LightCollection,
        data: &ObjectData3d,
        gpu_data: &mut dyn GpuData,
        _viewport_width: u32,
        _viewport_height: u32,
    ) {
        if !self.frame_written {
            self.frame_written = true;
            let (view, proj) = camera.view_transform_pair(pass);
            let eye = camera.eye();
            let key = Vec3::from(KEY_LIGHT).normalize();
            let frame = FrameUniforms {
                view: view.to_mat4().to_cols_array_2d(),
                proj: proj.to_cols_array_2d(),
                eye: [eye.x, eye.y, eye.z, 1.0],
                key: [key.x, key.y, key.z, 0.0],
            };
            Context::get().write_buffer(&self.frame_buffer, 0, bytemuck::bytes_of(&frame));
        }
        let s = Mat3::from_diagonal(scale).to_cols_array_2d();
        let c = data.color();
        let uniforms = ObjectUniforms {
            transform: transform.to_mat4().to_cols_array_2d(),
            scale: [
                [s[0][0], s[0][1], s[0][2], 0.0],
                [s[1][0], s[1][1], s[1][2], 0.0],
                [s[2][0], s[2][1], s[2][2], 0.0],
            ],
            color: [c.r, c.g, c.b, c.a],
            pattern: match self.checker {
                Some(size) => [1.0, size, 0.0, 0.0],
                None => [0.0; 4],
            },
        };
        let offset = self.objects.push(&uniforms);
        if let Some(g) = gpu_data.as_any_mut().downcast_mut::<FlatGpuData>() {
            g.offset = Some(offset);
        }
    }

    fn render(
        &mut self,
        _pass: usize,
        _transform: Pose3,
        _scale: Vec3,
        _camera: &mut dyn Camera3d,
        _lights: &LightCollection,
        data: &ObjectData3d,
        mesh: &mut GpuMesh3d,
        _instances: &mut InstancesBuffer3d,
        gpu_data: &mut dyn GpuData,
        render_pass: &mut wgpu::RenderPass<'_>,
        context: &RenderContext,
    ) {
        if !data.surface_rendering_active() || context.phase != kiss3d::resource::RenderPhase::Opaque {
            return;
        }
        let Some(offset) = gpu_data.as_any_mut().downcast_mut::<FlatGpuData>().and_then(|g| g.offset) else {
            return;
        };
        mesh.coords().write().expect("mesh lock").load_to_gpu();
        mesh.normals().write().expect("mesh lock").load_to_gpu();
        mesh.faces().write().expect("mesh lock").load_to_gpu();
        let (coords, normals, faces) = (mesh.coords().read(), mesh.normals().read(), mesh.faces().read());
        let (Ok(coords), Ok(normals), Ok(faces)) = (coords, normals, faces) else { return };
        let (Some(coords), Some(normals), Some(faces)) = (coords.buffer(), normals.buffer(), faces.buffer()) else {
            return;
        };
        let pipeline = if data.backface_culling_enabled() && !context.force_no_cull {
            self.cull.get(context.sample_count)
        } else {
            self.no_cull.get(context.sample_count)
        };
        render_pass.set_pipeline(&pipeline);
        render_pass.set_bind_group(0, &self.frame_group, &[]);
        render_pass.set_bind_group(1, &self.object_group, &[offset]);
        render_pass.set_vertex_buffer(0, coords.slice(..));
        render_pass.set_vertex_buffer(1, normals.slice(..));
        render_pass.set_index_buffer(faces.slice(..), VERTEX_INDEX_FORMAT);
        render_pass.draw_indexed(0..mesh.num_indices(), 0, 0..1);
    }
}
