//! Crashers: every input that once aborted, crashed or hung the process through the
//! safe API, one file per cause (named after it, the cause in its header). Each test
//! fails, or kills this test binary, if its crash comes back.

mod common;

mod ball_chain_with_extreme_mass_ratio;
mod cylinder_of_subnormal_length;
mod density_overflow;
mod diverging_velocity;
mod force_accumulated_every_step;
mod hash_space_body_far_away;
mod hash_space_inverted_levels;
mod hash_space_of_too_many_geoms;
mod heightfield_of_billions_of_vertices;
mod hinge2_attached_to_the_world;
mod huge_capsule_next_to_cone;
mod huge_time_step;
mod inertia_breaking_triangle_inequality;
mod long_capsule_against_cylinder_hang;
mod panicking_hook;
mod panicking_logger;
mod panicking_sensor;
mod pile_of_overlapping_boxes;
mod redundant_fixed_joints_with_zero_cfm;
mod rotation_matrix_with_huge_entries;
mod sensor_on_removed_object;
mod single_triangle_trimeshes;
mod tiny_and_huge_masses;
mod universal_axes_not_perpendicular;
mod urdf_loop_apart_from_the_root;
