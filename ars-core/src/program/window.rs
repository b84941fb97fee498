//! How a program wants to be shown: the viewer's window and camera.

/// How a program wants to be shown (the viewer's window and camera); the defaults
/// are the original's: 1024 × 768, camera at (10, 8, 10) looking at the origin, white
/// background.
#[derive(Clone, Debug, PartialEq)]
pub struct WindowSettings {
    /// Window title.
    pub title: String,
    /// Window (or off-screen image) size, pixels.
    pub size: (u32, u32),
    /// Where the camera is.
    pub camera_position: nalgebra::Point3<f64>,
    /// What it looks at.
    pub camera_target: nalgebra::Point3<f64>,
    /// Background colour (RGB in [0, 1]).
    pub background: [f32; 3],
    /// How finely to draw.
    pub quality: RenderQuality,
    /// The object the camera follows (by name; the window's `f` key toggles it).
    pub follow: Option<String>,
}

/// How the viewer draws.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub enum RenderQuality {
    /// Fast on a software rasteriser (no GPU), fine otherwise.
    #[default]
    Auto,
    /// Flat (Lambert) shading and a checkered floor, no shadows, no anti-aliasing:
    /// real time without a GPU.
    Fast,
    /// kiss3d's physically based materials and shadows.
    Fine,
}

impl Default for WindowSettings {
    fn default() -> Self {
        WindowSettings {
            title: "Autonomous Robot Simulator".into(),
            size: (1024, 768),
            camera_position: nalgebra::Point3::new(10.0, 8.0, 10.0),
            camera_target: nalgebra::Point3::origin(),
            background: [1.0, 1.0, 1.0],
            quality: RenderQuality::Auto,
            follow: None,
        }
    }
}
