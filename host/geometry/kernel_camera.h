// kernel_camera.h — host vectors written into the float4 fields of kernel parameter structs, and the
// pinhole camera's frame (cameraFrame, geometry/shafts_geometry.h) written into a struct's cam_pos,
// cam_right, cam_up and cam_forward. Every pass that casts camera rays on the device sets its frame
// here, so the kernels and the references (which call cameraFrame) see one camera.
#pragma once
#include <cmath>


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

// The frame, tan of half the vertical field of view and one pixel's angle (2 tan(fov/2) / height): what
// a camera moved at one image size changes in a struct that has these fields (the sea and the foam).
template <class KernelParams>
void setKernelCameraView(KernelParams& p, const CameraDesc& cam) {
  setKernelCamera(p, cam);
  p.tan_half_fov_y = static_cast<float>(std::tan(cam.fov_y / 2));
  p.pixel_angle = static_cast<float>(2 * std::tan(cam.fov_y / 2) / cam.height);
}

}  // namespace seasim
