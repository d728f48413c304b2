#pragma once
// Public: light a bake again, as often as the lights move.
//
//   bounce::LightingSession session("bakes/cornell-box");   // folder, scene, tracer, T b
//   session.move_light("ceiling-point", {0.0f, 1.5f, 0.0f});
//   session.light();                                        // b, T b per patch
//   const bounce::LitMesh mesh = session.lit_mesh();        // light per vertex
//   std::vector<glm::vec3> sh;                              // baked with --light-probes:
//   session.probe_sh(sh);                                   // 9 RGB SH per probe
//   // positions: session.light_probes()->position
//   std::array<glm::vec3, 9> at;                            // a moving object's light:
//   session.probe_sh_at({0.0f, 1.0f, 0.0f}, at);            // the probes that see it
//
// Light probes (runtime/light_probes.h): session.light_probes()->position
// holds each probe's position (float x, y, z) and probe_sh() its irradiance
// as real SH L2, 9 RGB coefficients per probe, probe p's coefficient j at
// p * 9 + j. E(n) = sum_j c_j Y_j(n) with the orthonormal real basis in the
// order (0,0), (1,-1), (1,0), (1,1), (2,-2), (2,-1), (2,0), (2,1), (2,2),
// Y_1 = 0.488603 y, Y_2 = 0.488603 z, Y_3 = 0.488603 x: the irradiance of
// light reflected at least once (the engine adds its lights' direct light).
// three.js's and Unity's radiance coefficients are c_j / A_l, A = pi,
// 2 pi / 3, pi / 4 for l = 0, 1, 2 (docs/bake-format.md, "Light probes").
// probe_sh_at() blends the SH of the probes around a point that see it, so
// no light crosses a wall (runtime/probe_interpolation.h).
//
// LightingSession (relight/lighting_session.h) is what every front end
// opens: it reads and checks the folder, loads the scene the bake was made
// from, builds the tracer and the Relighter (the product T b chosen once:
// dense, compressed in C++ with its block loop measured at load, or
// compressed on the OpenCL device), holds the lights by name, and takes each
// frame to the lit mesh's vertices or the camera's pixels through the bake's
// final gather, or from the nearest patches when it stored none. The pieces
// a frame is made of are public too, for front ends that run them one by
// one: the direct light on the patches (direct_light.h), the patches' light
// for a set of lights (PatchLighting), the dense product itself, and the
// gather from nearby patches over a grid (PatchGather). For a view of the
// patches of a bake read back: the light sets its probe lights them with,
// their radiosity, and the indirect-light error of its compressed matrix
// under a light set (bake_patch_light.h).
#include "bake/bake_patch_light.h"
#include "bake/camera_gather.h"
#include "bake/stored_transport.h"
#include "raytrace/ray_tracer.h"
#include "relight/lighting_session.h"
#include "runtime/area_lights.h"
#include "runtime/camera_image.h"
#include "runtime/dense_transport.h"
#include "runtime/direct_light.h"
#include "runtime/final_gather.h"
#include "runtime/final_gather_build.h"
#include "runtime/light_probes.h"
#include "runtime/mesh_transfer.h"
#include "runtime/patch_gather.h"
#include "runtime/patch_lighting.h"
#include "runtime/probe_interpolation.h"
#include "runtime/relighter.h"
#include "runtime/transport_multiplier.h"
