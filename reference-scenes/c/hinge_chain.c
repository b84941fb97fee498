/* Two hinged cylinders: the first hinged to the static world at (0, 1.9, 0), the
 * second to the first at (1, 1.9, 0), both axes +Z; both cylinders lie along +X
 * (local Z turned by pi/2 about Y), length 1, radius 0.1, 1 kg. A torque of 2 N m acts
 * on the first hinge every step; the chain swings down and its tip touches the plane
 * y = 0. */
#include "scenes.h"

static void push_first_hinge(ArsCScene *s)
{
    dJointAddHingeTorque(s->joints[0], s->torque);
}

static dBodyID link(ArsCScene *s, dReal cx)
{
    dMass m;
    dMatrix3 r;
    dBodyID b = dBodyCreate(s->world);
    dMassSetZero(&m);
    dMassSetCylinderTotal(&m, 1.0, 3, 0.1, 1.0);
    dBodySetMass(b, &m);
    dBodySetPosition(b, cx, 1.9, 0);
    ars_c_rotation_about_axis(0, 1, 0, M_PI / 2, r);
    dBodySetRotation(b, r);
    dGeomID g = dCreateCylinder(s->space, 0.1, 1.0);
    dGeomSetBody(g, b);
    s->bodies[s->body_count++] = b;
    return b;
}

ArsCScene *ars_c_hinge_chain_new(void)
{
    ArsCScene *s = ars_c_scene_alloc(0);
    dCreatePlane(s->space, 0, 1, 0, 0);
    dBodyID a = link(s, 0.5);
    dBodyID b = link(s, 1.5);

    dJointID j1 = dJointCreateHinge(s->world, 0);
    dJointAttach(j1, a, 0);
    dJointSetHingeAnchor(j1, 0, 1.9, 0);
    dJointSetHingeAxis(j1, 0, 0, 1);
    dJointID j2 = dJointCreateHinge(s->world, 0);
    dJointAttach(j2, a, b);
    dJointSetHingeAnchor(j2, 1, 1.9, 0);
    dJointSetHingeAxis(j2, 0, 0, 1);
    s->joints[s->joint_count++] = j1;
    s->joints[s->joint_count++] = j2;

    s->torque = 2.0;
    s->pre_step = push_first_hinge;
    return s;
}
