/* The thesis' laser example, as the ARS Simulation builds it (TwoBallLaser): floor
 * y = 0, balls r 1, 1 kg at (3,4,1) then (5,3,1), a 1000 m ray at (1.5,1.5,1) turned
 * pi/2 about Y (pointing +X). */
#include "scenes.h"

static dBodyID ball(ArsCScene *s, dReal x, dReal y, dReal z)
{
    dMass m;
    dBodyID b = dBodyCreate(s->world);
    dMassSetZero(&m);
    dMassSetSphereTotal(&m, 1.0, 1.0);
    dBodySetMass(b, &m);
    dBodySetPosition(b, x, y, z);
    dGeomID g = dCreateSphere(s->space, 1.0);
    dGeomSetBody(g, b);
    s->bodies[s->body_count++] = b;
    return b;
}

ArsCScene *ars_c_two_ball_laser_new(void)
{
    ArsCScene *s = ars_c_scene_alloc(0);
    dCreatePlane(s->space, 0, 1, 0, 0);
    ball(s, 3, 4, 1);
    ball(s, 5, 3, 1);
    dMatrix3 r;
    s->ray = dCreateRay(s->space, 1000.0);
    dGeomSetPosition(s->ray, 1.5, 1.5, 1.0);
    ars_c_rotation_about_axis(0, 1, 0, M_PI / 2, r);
    dGeomSetRotation(s->ray, r);
    s->ray_distance = -1;
    return s;
}
