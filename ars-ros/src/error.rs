//! What can go wrong recording or publishing.

/// An error of the ROS layer.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RosError {
    /// From the simulation.
    #[error(transparent)]
    Simulation(#[from] ars_core::Error),
    /// A message that could not be encoded or decoded.
    #[error("CDR encoding: {detail}")]
    Encoding {
        /// What was wrong.
        detail: String,
    },
    /// Writing an MCAP file.
    #[error("MCAP file {file}: {detail}")]
    Mcap {
        /// The file.
        file: String,
        /// What went wrong.
        detail: String,
    },
}

/// A result of the ROS layer.
pub type RosResult<T> = std::result::Result<T, RosError>;
