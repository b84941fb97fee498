//! The `.msg` definitions of the messages, and the `ros2msg` schemas made of them.
//!
//! A schema (MCAP's `ros2msg` encoding, what `ros2 bag` writes) is the message's own
//! definition, then for every type it uses, directly or not, a line of 80 `=`, a line
//! `MSG: package/Name`, and that type's definition. Field types are written with their
//! package, so no reader has to guess it.

/// Each type's definition (comments and constants left out), by `package/Name`.
const DEFINITIONS: [(&str, &str); 21] = [
    ("builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"),
    ("std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"),
    ("std_msgs/String", "string data\n"),
    ("rosgraph_msgs/Clock", "builtin_interfaces/Time clock\n"),
    ("geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"),
    ("geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"),
    ("geometry_msgs/Quaternion", "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"),
    ("geometry_msgs/Pose", "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"),
    ("geometry_msgs/Twist", "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n"),
    ("geometry_msgs/Transform", "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"),
    (
        "geometry_msgs/TransformStamped",
        "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n",
    ),
    ("geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"),
    ("geometry_msgs/TwistWithCovariance", "geometry_msgs/Twist twist\nfloat64[36] covariance\n"),
    ("tf2_msgs/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"),
    (
        "sensor_msgs/JointState",
        "std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\nfloat64[] effort\n",
    ),
    (
        "sensor_msgs/LaserScan",
        "std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n\
         float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n\
         float32[] ranges\nfloat32[] intensities\n",
    ),
    (
        "sensor_msgs/Imu",
        "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n\
         geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n\
         geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n",
    ),
    (
        "sensor_msgs/Image",
        "std_msgs/Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\n\
         uint32 step\nuint8[] data\n",
    ),
    (
        "sensor_msgs/RegionOfInterest",
        "uint32 x_offset\nuint32 y_offset\nuint32 height\nuint32 width\nbool do_rectify\n",
    ),
    (
        "sensor_msgs/CameraInfo",
        "std_msgs/Header header\nuint32 height\nuint32 width\nstring distortion_model\nfloat64[] d\n\
         float64[9] k\nfloat64[9] r\nfloat64[12] p\nuint32 binning_x\nuint32 binning_y\n\
         sensor_msgs/RegionOfInterest roi\n",
    ),
    (
        "nav_msgs/Odometry",
        "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n\
         geometry_msgs/TwistWithCovariance twist\n",
    ),
];

/// The definition of `package/Name`.
fn definition(short_name: &str) -> Option<&'static str> {
    DEFINITIONS.iter().find(|(n, _)| *n == short_name).map(|(_, d)| *d)
}

/// The message types a definition's fields use (those with a package), in order.
fn used_types(definition: &str) -> impl Iterator<Item = &str> {
    definition.lines().filter_map(|line| {
        let field_type = line.split_whitespace().next()?;
        let base = field_type.split('[').next()?;
        base.contains('/').then_some(base)
    })
}

/// The `ros2msg` schema of the message type `name` (`"sensor_msgs/msg/JointState"`,
/// or `"sensor_msgs/JointState"`): its definition, then each type it uses, directly or
/// not, once, in the order first met, each after a line of 80 `=` and `MSG: package/Name`. `None` for a type
/// this crate does not define.
pub fn schema(name: &str) -> Option<String> {
    let short = name.replacen("/msg/", "/", 1);
    let mut text = definition(&short)?.to_string();
    let mut seen = vec![short.clone()];
    let mut queue: Vec<String> = used_types(definition(&short)?).map(String::from).collect();
    while !queue.is_empty() {
        let next = queue.remove(0);
        if seen.contains(&next) {
            continue;
        }
        let body = definition(&next)?;
        text.push_str(&"=".repeat(80));
        text.push_str(&format!("\nMSG: {next}\n{body}"));
        queue.extend(used_types(body).map(String::from));
        seen.push(next);
    }
    Some(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_schema_lists_every_type_used_once_after_its_own_definition() {
        let odometry = schema("nav_msgs/msg/Odometry").unwrap();
        assert!(odometry.starts_with("std_msgs/Header header\nstring child_frame_id\n"), "{odometry}");
        for dependency in [
            "std_msgs/Header",
            "builtin_interfaces/Time",
            "geometry_msgs/PoseWithCovariance",
            "geometry_msgs/Pose",
            "geometry_msgs/Point",
            "geometry_msgs/Quaternion",
            "geometry_msgs/TwistWithCovariance",
            "geometry_msgs/Twist",
            "geometry_msgs/Vector3",
        ] {
            assert_eq!(odometry.matches(&format!("\nMSG: {dependency}\n")).count(), 1, "{dependency}:\n{odometry}");
        }
        assert_eq!(odometry.matches(&"=".repeat(80)).count(), 9);
        assert_eq!(schema("std_msgs/String").unwrap(), "string data\n");
        assert_eq!(schema("example_msgs/msg/Nothing"), None);
    }

    #[test]
    fn every_type_a_definition_uses_is_defined() {
        for (name, body) in DEFINITIONS {
            for used in used_types(body) {
                assert!(definition(used).is_some(), "{name} uses {used}");
            }
            assert!(schema(name).is_some());
        }
    }
}
