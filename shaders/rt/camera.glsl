// PinholeCamera (raytrace/camera.h) on the GPU, its basis and scales in double as
// there, shared by the GPU integrators.

uniform ivec2 u_size;  // the image
// The band of rows this dispatch traces, [u_firstRow, u_firstRow + u_rows): the
// output holds those rows only.
uniform int u_firstRow, u_rows;

// This invocation's pixel, and whether it lies in the band.
ivec2 bandPixel(out bool inside) {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy) + ivec2(0, u_firstRow);
  inside = pixel.x < u_size.x && pixel.y < min(u_size.y, u_firstRow + u_rows);
  return pixel;
}
// Its place in the band's output.
int bandIndex(ivec2 pixel) { return (pixel.y - u_firstRow) * u_size.x + pixel.x; }
uniform dvec3 u_cameraPosition, u_cameraRight, u_cameraUp, u_cameraForward;
uniform dvec2 u_cameraScale;  // xScale, yScale
uniform double u_farPlane;

// generateRay and clippedToFarPlane: the direction formed in double, rounded once.
vec3 primaryRay(double px, double py, out float tMax) {
  double x = (2.0lf * px / double(u_size.x) - 1.0lf) * u_cameraScale.x;
  double y = -(2.0lf * py / double(u_size.y) - 1.0lf) * u_cameraScale.y;
  precise dvec3 v = dvec3(x, y, 1.0lf);
  precise dvec3 local = v * (1.0lf / sqrt(v.x * v.x + v.y * v.y + v.z * v.z));
  precise dvec3 d = local.x * u_cameraRight + local.y * u_cameraUp + local.z * u_cameraForward;
  vec3 df = vec3(d);
  float tMax0 = rtInfinity();
  precise double depthPerT = double(df.x) * u_cameraForward.x + double(df.y) * u_cameraForward.y + double(df.z) * u_cameraForward.z;
  if (depthPerT > 0.0lf) tMax0 = min(tMax0, float(u_farPlane / depthPerT));
  tMax = tMax0;
  return df;
}
