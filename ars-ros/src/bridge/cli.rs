//! The bridge's command-line options (`ars ros FILE ...`, and the examples' `--ros`),
//! read with `clap`.

use super::{BridgeOptions, ServiceRmw};

/// How `ars ros` runs the bridge.
#[derive(clap::Args, Clone, Debug)]
pub struct RosArgs {
    /// Start paused: the simulation advances only through the StepSimulation service
    /// (/ars/step_simulation), bit for bit as `ars run` would
    #[arg(long)]
    pub lock_step: bool,
    /// The ROS domain ID, 0 to 232 (default: ROS_DOMAIN_ID, else 0)
    #[arg(long, value_name = "ID")]
    pub domain_id: Option<u16>,
    /// State publications (/clock, /tf, /joint_states, /odom) per simulated second
    #[arg(long, value_name = "HZ", default_value_t = 50.0, value_parser = positive_rate)]
    pub rate: f64,
    /// The differential drive /cmd_vel turns: its two wheel joints (default: w1,w2, or
    /// the hinges named *left*wheel* and *right*wheel*)
    #[arg(long, value_name = "JOINT,JOINT", value_parser = two_names)]
    pub drive: Option<(String, String)>,
    /// The most torque a drive wheel's motor puts out, N·m
    #[arg(long, value_name = "NM", default_value_t = 30.0, value_parser = positive_torque)]
    pub wheel_torque: f64,
    /// Whose service calls to answer: fastrtps (ROS 2's default) or cyclonedds
    /// (default: from RMW_IMPLEMENTATION)
    #[arg(long, value_name = "RMW", value_parser = rmw)]
    pub services: Option<ServiceRmw>,
}

impl RosArgs {
    /// The bridge's options, to stop after `duration` simulated seconds (`None`: until
    /// Ctrl-C or a `SetSimulationState` to quit).
    pub fn options(&self, duration: Option<f64>) -> Result<BridgeOptions, String> {
        let domain_id = match (self.domain_id, std::env::var("ROS_DOMAIN_ID")) {
            (Some(id), _) => id,
            (None, Ok(text)) if !text.trim().is_empty() => {
                text.trim().parse().map_err(|_| format!("ROS_DOMAIN_ID={text:?} is not a domain ID (0 to 232)"))?
            }
            _ => 0,
        };
        Ok(BridgeOptions {
            domain_id,
            lock_step: self.lock_step,
            rate: self.rate,
            services: self.services.unwrap_or_else(ServiceRmw::from_env),
            drive: self.drive.clone(),
            wheel_torque: self.wheel_torque,
            duration,
            ..Default::default()
        })
    }
}

fn positive(v: &str, unit: &str) -> Result<f64, String> {
    match v.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("must be a positive number {unit}, got {v:?}")),
    }
}

fn positive_rate(v: &str) -> Result<f64, String> {
    positive(v, "per second")
}

fn positive_torque(v: &str) -> Result<f64, String> {
    positive(v, "of N·m")
}

fn two_names(v: &str) -> Result<(String, String), String> {
    match v.split(',').map(str::trim).collect::<Vec<_>>()[..] {
        [a, b] if !a.is_empty() && !b.is_empty() => Ok((a.to_string(), b.to_string())),
        _ => Err(format!("must name two wheel joints, like left_wheel_joint,right_wheel_joint, got {v:?}")),
    }
}

fn rmw(v: &str) -> Result<ServiceRmw, String> {
    match v.to_lowercase().as_str() {
        "fastrtps" | "rmw_fastrtps_cpp" | "fastdds" => Ok(ServiceRmw::FastRtps),
        "cyclonedds" | "rmw_cyclonedds_cpp" => Ok(ServiceRmw::CycloneDds),
        _ => Err(format!("must be fastrtps or cyclonedds, got {v:?}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser)]
    struct Cli {
        #[command(flatten)]
        ros: RosArgs,
    }

    #[test]
    fn the_options_are_read_and_checked() {
        let cli = Cli::try_parse_from([
            "ars",
            "--lock-step",
            "--domain-id",
            "7",
            "--drive",
            "l, r",
            "--services",
            "cyclonedds",
        ])
        .expect("good options");
        let options = cli.ros.options(Some(2.0)).expect("options");
        assert!(options.lock_step && options.rate == 50.0 && options.duration == Some(2.0));
        assert_eq!((options.domain_id, options.services), (7, ServiceRmw::CycloneDds));
        assert_eq!(options.drive, Some(("l".into(), "r".into())));
        let refused = |args: &[&str]| Cli::try_parse_from(args).err().expect("refused").to_string();
        assert!(refused(&["ars", "--drive", "one"]).contains("must name two wheel joints"));
        assert!(refused(&["ars", "--rate", "0"]).contains("positive number per second"));
        assert!(refused(&["ars", "--services", "zenoh"]).contains("fastrtps or cyclonedds"));
    }
}
