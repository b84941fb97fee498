//! The viewer's errors.

/// What can go wrong in the viewer.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum ViewerError {
    /// No GPU adapter (not even Mesa's software rasterisers) could be found.
    #[error(
        "no graphics adapter found ({0}); for off-screen rendering with no GPU install Mesa's software drivers: \
         sudo apt-get install libvulkan1 mesa-vulkan-drivers libegl1 libegl-mesa0 libgl1-mesa-dri"
    )]
    NoAdapter(String),
    /// The simulation failed.
    #[error(transparent)]
    Simulation(#[from] ars_core::Error),
    /// Writing a frame failed.
    #[error("could not write {path}: {message}")]
    Write {
        /// The file.
        path: String,
        /// Why.
        message: String,
    },
    /// A bad recorder or viewer setting.
    #[error("{0}")]
    Settings(String),
}

/// `Result` with [`ViewerError`].
pub type Result<T, E = ViewerError> = std::result::Result<T, E>;
