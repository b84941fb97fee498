/* The IROS mobile manipulators (examples 3 and 4), as the ARS programs SpeedProfile
 * and SinusoidalTerrain build and drive them: build_vehicle + build_vehicle_arm with
 * 1 kg links, dt 0.25 ms, and their pre-step hooks. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "scenes.h"

static dBodyID body(ArsCScene *s, dMass *m, dReal x, dReal y, dReal z)
{
    dBodyID b = dBodyCreate(s->world);
    dBodySetMass(b, m);
    dBodySetPosition(b, x, y, z);
    s->bodies[s->body_count++] = b;
    return b;
}

static dJointID hinge(ArsCScene *s, dBodyID a, dBodyID b, const dReal *anchor, dReal x, dReal y, dReal z)
{
    dJointID j = dJointCreateHinge(s->world, 0);
    dJointAttach(j, a, b);
    dJointSetHingeAnchor(j, anchor[0], anchor[1], anchor[2]);
    dJointSetHingeAxis(j, x, y, z);
    dJointSetFeedback(j, &s->feedback[s->joint_count]);
    s->joints[s->joint_count++] = j;
    return j;
}

/* Joints: 0 w1, 1 w2, 2 bs, 3 r1, 4 r2. */
static void build(ArsCScene *s, dReal ox, dReal oy, dReal oz)
{
    dMass m;
    dMassSetZero(&m);
    dMassSetSphere(&m, 1.0, 0.3);
    dBodyID ball = body(s, &m, 1, 0, 0);
    dGeomSetBody(dCreateSphere(s->space, 0.3), ball);
    dMassSetZero(&m);
    dMassSetBoxTotal(&m, 6.0, 2.0, 0.2, 1.5);
    dBodyID chassis = body(s, &m, 0.5, 0.45, 0);
    dGeomSetBody(dCreateBox(s->space, 2.0, 0.2, 1.5), chassis);
    dBodyID wheels[2];
    for (int i = 0; i < 2; i++) {
        dMassSetZero(&m);
        dMassSetCylinder(&m, 1.0, 3, 0.3, 0.4);
        wheels[i] = body(s, &m, 0, 0, i == 0 ? -0.5 : 0.5);
        dGeomSetBody(dCreateCylinder(s->space, 0.3, 0.4), wheels[i]);
    }
    hinge(s, chassis, wheels[0], dBodyGetPosition(wheels[0]), 0, 0, 1);
    hinge(s, chassis, wheels[1], dBodyGetPosition(wheels[1]), 0, 0, 1);
    const dReal *bp = dBodyGetPosition(ball);
    dJointID bs = dJointCreateBall(s->world, 0);
    dJointAttach(bs, chassis, ball);
    dJointSetBallAnchor(bs, bp[0], bp[1], bp[2]);
    dJointSetFeedback(bs, &s->feedback[s->joint_count]);
    s->joints[s->joint_count++] = bs;
    dBodyID parts[4] = {ball, chassis, wheels[0], wheels[1]};
    for (int i = 0; i < 4; i++)
        ars_c_offset(parts[i], ox, oy, oz);

    dMassSetZero(&m);
    dMassSetCapsuleTotal(&m, 1.0, 3, 0.1, 0.8);
    dBodyID link1 = body(s, &m, 0, 0, 0);
    dGeomSetBody(dCreateCapsule(s->space, 0.1, 0.8), link1);
    dMassSetZero(&m);
    dMassSetCapsuleTotal(&m, 1.0, 3, 0.1, 0.6);
    dBodyID link2 = body(s, &m, 0, 0.7, 0.2);
    dGeomSetBody(dCreateCapsule(s->space, 0.1, 0.6), link2);
    ars_c_rotate(link1, 1, 0, 0, M_PI / 2);
    ars_c_rotate(link2, 1, 0, 0, M_PI / 2);
    const dReal *c = dBodyGetPosition(chassis);
    ars_c_offset(link1, c[0], c[1], c[2]);
    ars_c_offset(link1, 0, 0.5, 0);
    const dReal *l1 = dBodyGetPosition(link1);
    ars_c_offset(link2, l1[0], l1[1], l1[2]);
    hinge(s, chassis, link1, dBodyGetPosition(link1), 0, 1, 0);
    const dReal *l2 = dBodyGetPosition(link2);
    dReal anchor[3] = {l2[0] - 0.0, l2[1] - 0.3, l2[2] - 0.0};
    hinge(s, link1, link2, anchor, 0, 0, 1);

    s->chassis = chassis;
    s->wheels[0] = wheels[0];
    s->wheels[1] = wheels[1];
    s->dt = 1.0 / 50.0 / 80.0;
}

/* ars_core::Profile::value for the thesis' trapezoid. */
static dReal profile(dReal time)
{
    static const dReal p[6][2] = {{0, 0}, {1, 0}, {5, 1}, {9, 1}, {13, 0}, {14, 0}};
    if (time <= p[0][0])
        return p[0][1];
    for (int i = 0; i < 5; i++) {
        dReal t0 = p[i][0], v0 = p[i][1], t1 = p[i + 1][0], v1 = p[i + 1][1];
        if (time <= t1) {
            if (t1 == t0)
                return v1;
            return v0 + (v1 - v0) * (time - t0) / (t1 - t0);
        }
    }
    return p[5][1];
}

static void speed_profile_pre_step(ArsCScene *s)
{
    dReal time = s->time;
    const dReal *v = dBodyGetLinearVel(s->chassis);
    dReal sign = v[0] > 0.0 ? 1.0 : -1.0;
    dReal speed = sqrt(v[0] * v[0] + v[2] * v[2]) * sign;
    dReal setpoint = profile(time);
    dReal error = setpoint - speed;
    dReal torque = 10.0 * error;
    dJointAddHingeTorque(s->joints[0], torque);
    dJointAddHingeTorque(s->joints[1], torque);
    dReal q1 = dJointGetHingeAngle(s->joints[3]), q1r = dJointGetHingeAngleRate(s->joints[3]);
    dReal q2 = dJointGetHingeAngle(s->joints[4]), q2r = dJointGetHingeAngleRate(s->joints[4]);
    dJointAddHingeTorque(s->joints[3], -0.02 * q1r);
    dJointAddHingeTorque(s->joints[4], -0.02 * q2r);
    dReal row[9] = {time, dBodyGetPosition(s->chassis)[0], setpoint, speed, torque, q1, q1r, q2, q2r};
    memcpy(s->row, row, sizeof row);
}

ArsCScene *ars_c_speed_profile_new(void)
{
    ArsCScene *s = ars_c_scene_alloc(0);
    dCreatePlane(s->space, 0, 1, 0, 0);
    build(s, -4.0, 0.5, 4.0);
    s->pre_step = speed_profile_pre_step;
    return s;
}

/* ars_core::Pid::update with kp 20, ki 0, kd 15. */
static dReal pd(dReal state[2], dReal error, dReal dt)
{
    state[0] += error * dt;
    dReal derivative = dt > 0.0 ? (error - state[1]) / dt : 0.0;
    state[1] = error;
    return 20.0 * error + 0.0 * state[0] + 15.0 * derivative;
}

static void terrain_pre_step(ArsCScene *s)
{
    const dReal *v = dBodyGetLinearVel(s->chassis);
    dReal speed = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    dReal wheel_torque = speed < 2.0 ? 4.0 : 0.0;
    dJointAddHingeTorque(s->joints[0], wheel_torque);
    dJointAddHingeTorque(s->joints[1], wheel_torque);
    dReal q1 = dJointGetHingeAngle(s->joints[3]), q1r = dJointGetHingeAngleRate(s->joints[3]);
    dReal q2 = dJointGetHingeAngle(s->joints[4]), q2r = dJointGetHingeAngleRate(s->joints[4]);
    dJointAddHingeTorque(s->joints[3], -0.02 * q1r);
    dJointAddHingeTorque(s->joints[4], -0.02 * q2r);
    dReal t1 = pd(s->pd_state[0], 0.0 - q1, s->dt);
    dReal t2 = pd(s->pd_state[1], 0.0 - q2, s->dt);
    dJointAddHingeTorque(s->joints[3], t1);
    dJointAddHingeTorque(s->joints[4], t2);
    const dReal *p = dBodyGetPosition(s->chassis);
    dReal row[9] = {s->time, p[0], p[1], p[2], q1, t1, q2, t2, wheel_torque};
    memcpy(s->row, row, sizeof row);
}

ArsCScene *ars_c_sinusoidal_terrain_new(void)
{
    ArsCScene *s = ars_c_scene_alloc(0);
    const int nx = 40, nz = 20;
    s->trimesh_vertices = malloc(sizeof(dReal) * 3 * nx * nz);
    for (int x = 0; x < nx; x++)
        for (int z = 0; z < nz; z++) {
            dReal *v = &s->trimesh_vertices[3 * (nz * x + z)];
            v[0] = (dReal)x;
            v[1] = sin((dReal)x * 0.5) * 0.7;
            v[2] = (dReal)z;
        }
    /* ars_core::heightfield_faces(40, 20). */
    int faces = 2 * (nx - 1) * (nz - 1);
    s->trimesh_indices = malloc(sizeof(dTriIndex) * 3 * faces);
    int k = 0;
    for (int x = 0; x < nx - 1; x++)
        for (int z = 0; z < nz - 1; z++) {
            dTriIndex i00 = nz * x + z, i01 = nz * x + z + 1, i10 = nz * (x + 1) + z, i11 = nz * (x + 1) + z + 1;
            unsigned type = (nz * x + z) + (nz % 2 == 0 ? 1 : 0);
            dTriIndex t[6];
            if (type % 2 == 0) {
                dTriIndex e[6] = {i00, i11, i10, i00, i01, i11};
                memcpy(t, e, sizeof t);
            } else {
                dTriIndex o[6] = {i00, i01, i10, i01, i11, i10};
                memcpy(t, o, sizeof t);
            }
            memcpy(&s->trimesh_indices[k], t, sizeof t);
            k += 6;
        }
    s->trimesh = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildDouble(s->trimesh, s->trimesh_vertices, 3 * sizeof(dReal), nx * nz, s->trimesh_indices, 3 * faces,
                                3 * sizeof(dTriIndex));
    dGeomID floor = dCreateTriMesh(s->space, s->trimesh, 0, 0, 0);
    dGeomSetPosition(floor, -10.0, 0.0, -10.0);
    dQuaternion identity = {1, 0, 0, 0};
    dGeomSetQuaternion(floor, identity);
    build(s, -1.05, -0.35, 5.0);
    s->pre_step = terrain_pre_step;
    return s;
}
