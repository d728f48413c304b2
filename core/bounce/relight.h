#pragma once
// Public: light a bake again, as often as the lights move.
//
//   const bounce::LoadedBake bake = bounce::BakeReader::read(folder);
//   const bounce::RayTracer tracer(scene);
//   bounce::Relighter relighter(tracer, bake.samples, bake.patches,
//                               bounce::stored_transport(bake));
//   relighter.light(scene.lights, bounce::area_lights(scene));
//   relighter.gather(*bounce::read_final_gather(folder, bake.size(), bake.samples.samples.size()),
//   per_vertex);
//
// The product T b is chosen once (RelighterSettings::multiply: dense,
// compressed in C++ with its block loop measured at load, or compressed on
// the OpenCL device); a frame runs through the frame graph without
// allocating; the final gather takes the patches' reflected light b + T b
// to the lit mesh's vertices (the gather a bake stores; the mesh from
// build_transfer_mesh) or to camera pixels (build_final_gather over the
// hits of render_camera_direct). The pieces a frame is made of are public
// too, for front ends that run them one by one: the direct light on the
// patches (direct_light.h), the patches' light for a set of lights
// (PatchLighting), the dense product itself, and the gather from nearby
// patches over a grid (PatchGather), which a bake without a stored final
// gather uses. For a view of the patches of a bake read back: the light
// sets its probe lights them with, their radiosity, and the indirect-light
// error of its compressed matrix under a light set (bake_patch_light.h).
#include "bake/bake_patch_light.h"
#include "bake/camera_gather.h"
#include "bake/stored_transport.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_lights.h"
#include "runtime/camera_image.h"
#include "runtime/dense_transport.h"
#include "runtime/direct_light.h"
#include "runtime/final_gather.h"
#include "runtime/mesh_transfer.h"
#include "runtime/patch_gather.h"
#include "runtime/patch_lighting.h"
#include "runtime/relighter.h"
#include "runtime/transport_multiplier.h"
