/* The ARS step and near callback in plain C (see scenes.h). */
#include <stdlib.h>
#include <string.h>
#include "scenes.h"

/* The caller has initialised ODE and its data for this thread (the Rust side calls
 * ars_core::ensure_ode_ready). ARS' world: gravity (0,-9.81,0), ERP 0.2, CFM 1e-10, one contact group, one space. */
ArsCScene *ars_c_scene_alloc(int hash_space)
{
    ArsCScene *s = calloc(1, sizeof *s);
    s->world = dWorldCreate();
    dWorldSetGravity(s->world, 0, -9.81, 0);
    dWorldSetERP(s->world, 0.2);
    dWorldSetCFM(s->world, 1e-10);
    /* Each world its own (self-threaded) step job queue: ODE's default one is shared
     * by the whole process and is not safe to use from several threads. */
    s->threading = dThreadingAllocateSelfThreadedImplementation();
    dWorldSetStepThreadingImplementation(s->world, dThreadingImplementationGetFunctions(s->threading),
                                         s->threading);
    s->contacts = dJointGroupCreate(0);
    if (hash_space) {
        s->space = dHashSpaceCreate(0);
        dHashSpaceSetLevels(s->space, -3, 10);
    } else {
        s->space = dSimpleSpaceCreate(0);
    }
    dSpaceSetCleanup(s->space, 0);
    s->dt = 0.0004;
    return s;
}

/* Rodrigues' formula, term by term as ars_core::convert::rotation_about_axis. */
void ars_c_rotation_about_axis(dReal x, dReal y, dReal z, dReal angle, dMatrix3 r)
{
    dReal c = cos(angle), s = sin(angle), t = 1.0 - c;
    memset(r, 0, sizeof(dMatrix3));
    r[0] = t * x * x + c;     r[1] = t * x * y - s * z; r[2] = t * x * z + s * y;
    r[4] = t * x * y + s * z; r[5] = t * y * y + c;     r[6] = t * y * z - s * x;
    r[8] = t * x * z - s * y; r[9] = t * y * z + s * x; r[10] = t * z * z + c;
}

static int is_ray(dGeomID g) { return dGeomGetClass(g) == dRayClass; }

/* The ARS near callback: skip jointed bodies, rays make no contacts, every other
 * contact point gets bounce 0.2 (above 0 m/s) and a 500 N friction limit. */
static void near_callback(void *data, dGeomID o1, dGeomID o2)
{
    ArsCScene *s = data;
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (b1 && b2 && dAreConnectedExcluding(b1, b2, dJointTypeContact))
        return;
    if (is_ray(o1) && is_ray(o2))
        return;
    int n = dCollide(o1, o2, ARS_C_MAX_CONTACTS, s->scratch, sizeof(dContactGeom));
    if (is_ray(o1) || is_ray(o2)) {
        for (int i = 0; i < n; i++)
            if (s->ray_distance < 0 || s->scratch[i].depth < s->ray_distance)
                s->ray_distance = s->scratch[i].depth;
        return;
    }
    for (int i = 0; i < n; i++) {
        dContact contact;
        memset(&contact, 0, sizeof contact);
        contact.surface.mode = dContactBounce;
        contact.surface.mu = 500.0;
        contact.surface.bounce = 0.2;
        contact.surface.bounce_vel = 0.0;
        contact.geom = s->scratch[i];
        dJointID j = dJointCreateContact(s->world, s->contacts, &contact);
        dJointAttach(j, b1, b2);
    }
}

void ars_c_scene_step(ArsCScene *s, int steps)
{
    for (int i = 0; i < steps; i++) {
        if (s->pre_step)
            s->pre_step(s);
        s->ray_distance = -1;
        dSpaceCollide(s->space, s, near_callback);
        dWorldStep(s->world, s->dt);
        s->time += s->dt;
        dJointGroupEmpty(s->contacts);
    }
}

int ars_c_scene_body_count(const ArsCScene *s) { return s->body_count; }
dReal ars_c_scene_ray_distance(const ArsCScene *s) { return s->ray_distance; }
dReal ars_c_scene_time(const ArsCScene *s) { return s->time; }
void ars_c_scene_row(const ArsCScene *s, dReal out[9]) { memcpy(out, s->row, sizeof s->row); }

void ars_c_rotate(dBodyID body, dReal x, dReal y, dReal z, dReal angle)
{
    dMatrix3 turn, out;
    const dReal *cur = dBodyGetRotation(body);
    ars_c_rotation_about_axis(x, y, z, angle, turn);
    memset(out, 0, sizeof out);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            out[4 * i + j] = turn[4 * i + 0] * cur[0 + j] + turn[4 * i + 1] * cur[4 + j] + turn[4 * i + 2] * cur[8 + j];
    dBodySetRotation(body, out);
}

void ars_c_offset(dBodyID body, dReal x, dReal y, dReal z)
{
    const dReal *p = dBodyGetPosition(body);
    dBodySetPosition(body, p[0] + x, p[1] + y, p[2] + z);
}

void ars_c_scene_body_state(const ArsCScene *s, int index, dReal out[13])
{
    dBodyID b = s->bodies[index];
    const dReal *p = dBodyGetPosition(b), *q = dBodyGetQuaternion(b);
    const dReal *v = dBodyGetLinearVel(b), *w = dBodyGetAngularVel(b);
    for (int k = 0; k < 3; k++) out[k] = p[k];
    for (int k = 0; k < 4; k++) out[3 + k] = q[k];
    for (int k = 0; k < 3; k++) out[7 + k] = v[k];
    for (int k = 0; k < 3; k++) out[10 + k] = w[k];
}

void ars_c_scene_free(ArsCScene *s)
{
    dJointGroupEmpty(s->contacts);
    dJointGroupDestroy(s->contacts);
    for (int i = 0; i < s->joint_count; i++)
        dJointDestroy(s->joints[i]);
    /* Geoms are destroyed with the space here (cleanup on); the Rust world destroys
     * them one by one. Neither affects the trajectories. */
    dSpaceSetCleanup(s->space, 1);
    dSpaceDestroy(s->space);
    if (s->trimesh) {
        dGeomTriMeshDataDestroy(s->trimesh);
        free(s->trimesh_vertices);
        free(s->trimesh_indices);
    }
    dWorldSetStepThreadingImplementation(s->world, NULL, NULL);
    dThreadingFreeImplementation(s->threading);
    dWorldDestroy(s->world);
    free(s);
}
