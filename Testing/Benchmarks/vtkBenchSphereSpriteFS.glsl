//VTK::Color::Impl
  // An opaque sphere-shaded sprite for vtkPointGaussianMapper (VTK's
  // examples' shading), so that the peer draws solid points, not blobs.
  float dist = dot(offsetVCVSOutput.xy, offsetVCVSOutput.xy);
  if (dist > 1.0) { discard; } else {
    float scale = (1.0 - dist);
    ambientColor *= scale;
    diffuseColor *= scale;
  }
