// kernel_camera.h — host vectors written into the float4 fields of kernel parameter structs, and the
// pinhole camera's frame (cameraFrame, geometry/shafts_geometry.h) written into a struct's cam_pos,
// cam_right, cam_up and cam_forward. Every pass that casts camera rays on the device sets its frame
// here, so the kernels and the references (which call cameraFrame) see one camera.
#pragma once

#include "geometry/shafts_geometry.h"
#include "math/vec3.h"
#include "scene/scene.h"

namespace seasim {

inline void set4(float out[4], Vec3 v, double w = 0.0) {
  out[0] = static_cast<float>(v.x);
  out[1] = static_cast<float>(v.y);
  out[2] = static_cast<float>(v.z);
  out[3] = static_cast<float>(w);
}

template <class KernelParams>
void setKernelCamera(KernelParams& p, const CameraDesc& cam) {
  const CameraFrame f = cameraFrame(cam);
  set4(p.cam_pos, f.eye);
  set4(p.cam_right, f.right);
  set4(p.cam_up, f.up);
  set4(p.cam_forward, f.fwd);
}

}  // namespace seasim
