/* Reference scenes written in plain C against the system libode, with the same ODE
 * calls in the same order as the Rust port, so that tests and benchmarks can hold the
 * Rust code against native ODE. Compiled by the root build.rs. */
#ifndef ARS_C_SCENES_H
#define ARS_C_SCENES_H

#include <ode/ode.h>

#define ARS_C_MAX_BODIES 256
#define ARS_C_MAX_CONTACTS 150

typedef struct ArsCScene ArsCScene;

struct ArsCScene {
    dWorldID world;
    dThreadingImplementationID threading;
    dSpaceID space;
    dJointGroupID contacts;
    dReal dt;
    int body_count;
    dBodyID bodies[ARS_C_MAX_BODIES];
    dJointID joints[8];
    dJointFeedback feedback[8];
    int joint_count;
    dReal torque;                      /* hinge chain: torque on joint 0 every step */
    dReal time;                        /* accumulated like the Rust simulation: time += dt */
    dGeomID ray;                       /* a laser's ray, or 0 */
    dReal ray_distance;                /* closest hit of the last collision, or -1 */
    dReal rates[2];                    /* conical pendulum: joint rates of the last step */
    dBodyID chassis, wheels[2];        /* mobile manipulators */
    dReal pd_state[2][2];              /* per arm joint: PID integral, previous error */
    dReal row[9];                      /* what the last pre-step hook recorded */
    dTriMeshDataID trimesh;
    dReal *trimesh_vertices;
    dTriIndex *trimesh_indices;
    void (*pre_step)(ArsCScene *scene);
    dContactGeom scratch[ARS_C_MAX_CONTACTS];
};

/* Common pieces (common.c). */
ArsCScene *ars_c_scene_alloc(int hash_space);
void ars_c_rotation_about_axis(dReal x, dReal y, dReal z, dReal angle, dMatrix3 r);

/* The scenes. */
ArsCScene *ars_c_falling_sphere_new(void);
ArsCScene *ars_c_hinge_chain_new(void);
ArsCScene *ars_c_drop_pile_new(int count);
ArsCScene *ars_c_two_ball_laser_new(void);
ArsCScene *ars_c_conical_pendulum_new(void);
ArsCScene *ars_c_speed_profile_new(void);
ArsCScene *ars_c_sinusoidal_terrain_new(void);
void ars_c_scene_row(const ArsCScene *scene, dReal out[9]);

/* Run `steps` steps: pre-step hook, collide, dWorldStep, empty the contact group. */
void ars_c_scene_step(ArsCScene *scene, int steps);
int ars_c_scene_body_count(const ArsCScene *scene);
/* position (3), quaternion w x y z (4), linear velocity (3), angular velocity (3). */
void ars_c_scene_body_state(const ArsCScene *scene, int index, dReal out[13]);
void ars_c_scene_free(ArsCScene *scene);
dReal ars_c_scene_ray_distance(const ArsCScene *scene);
dReal ars_c_scene_time(const ArsCScene *scene);
/* The ARS Simulation's rotate(): R <- R(axis, angle) * R, summed left to right. */
void ars_c_rotate(dBodyID body, dReal x, dReal y, dReal z, dReal angle);
void ars_c_offset(dBodyID body, dReal x, dReal y, dReal z);

#endif
