/* IROS example 2 (the conical pendulum), as the ARS ConicalPendulum program builds and
 * drives it: dt 0.25 ms, floor y = -0.5, a 5000 kg free base box, pole and arm
 * cylinders turned pi/2 about X and offset by (1,0,2), waist and shoulder hinges with
 * feedback, waist torque 20 t (20 after 1 s) and friction -5 * previous rate. */
#include "scenes.h"

static void pendulum_pre_step(ArsCScene *s)
{
    dReal t = s->time;
    dReal torque = t < 1.0 ? 20.0 * t / 1.0 : 20.0;
    dReal friction = 50e-3 * 100.0;
    dJointAddHingeTorque(s->joints[0], torque);
    dJointAddHingeTorque(s->joints[0], -friction * s->rates[0]);
    dJointAddHingeTorque(s->joints[1], -friction * s->rates[1]);
    s->rates[0] = dJointGetHingeAngleRate(s->joints[0]);
    s->rates[1] = dJointGetHingeAngleRate(s->joints[1]);
}

static dBodyID cylinder(ArsCScene *s, dReal x, dReal y, dReal z)
{
    dMass m;
    dBodyID b = dBodyCreate(s->world);
    dMassSetZero(&m);
    dMassSetCylinderTotal(&m, 10.0, 3, 0.141421, 1.0);
    dBodySetMass(b, &m);
    dBodySetPosition(b, x, y, z);
    dGeomID g = dCreateCylinder(s->space, 0.141421, 1.0);
    dGeomSetBody(g, b);
    s->bodies[s->body_count++] = b;
    return b;
}

static dJointID hinge(ArsCScene *s, dBodyID a, dBodyID b, dReal ax, dReal ay, dReal az, dReal x, dReal y, dReal z)
{
    dJointID j = dJointCreateHinge(s->world, 0);
    dJointAttach(j, a, b);
    dJointSetHingeAnchor(j, ax, ay, az);
    dJointSetHingeAxis(j, x, y, z);
    dJointSetFeedback(j, &s->feedback[s->joint_count]);
    s->joints[s->joint_count++] = j;
    return j;
}

ArsCScene *ars_c_conical_pendulum_new(void)
{
    ArsCScene *s = ars_c_scene_alloc(0);
    s->dt = 1.0 / 50.0 / 80.0;
    dCreatePlane(s->space, 0, 1, 0, -0.5);

    dMass m;
    dBodyID base = dBodyCreate(s->world);
    dMassSetZero(&m);
    dMassSetBox(&m, 100.0, 10.0, 0.5, 10.0);
    dBodySetMass(base, &m);
    dBodySetPosition(base, 0.0 + 1.0, -0.25 + 0.0, 0.0 + 2.0);
    dGeomID g = dCreateBox(s->space, 10.0, 0.5, 10.0);
    dGeomSetBody(g, base);
    s->bodies[s->body_count++] = base;

    dBodyID pole = cylinder(s, 0, 0.51, 0);
    dBodyID arm = cylinder(s, 0, 0.51, 0.1);
    ars_c_rotate(pole, 1, 0, 0, M_PI / 2);
    ars_c_offset(pole, 1, 0, 2);
    ars_c_rotate(arm, 1, 0, 0, M_PI / 2);
    ars_c_offset(arm, 1, 0, 2);

    const dReal *p = dBodyGetPosition(pole);
    hinge(s, base, pole, p[0], p[1], p[2], 0, 1, 0);
    hinge(s, pole, arm, 0.0 + 1.0, 1.01 + 0.0, 0.1 + 2.0, 1, 0, 0);
    s->pre_step = pendulum_pre_step;
    return s;
}
