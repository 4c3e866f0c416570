// The optics of the model (paper eq. 4-9, docs/design.md §3.1), shared by the passes.

const float OPAL_PI = 3.14159265358979;

// Unpolarised Fresnel reflectance of a dielectric seen from the medium of
// index 1 towards index mu, for the cosine of the incidence angle (paper §6.1).
float fresnelReflectance(float cosIncidence, float mu)
{
  float c = clamp(cosIncidence, 0.0, 1.0);
  float sinT2 = (1.0 - c * c) / (mu * mu);
  if (sinT2 >= 1.0)
  {
    return 1.0;
  }
  float cosT = sqrt(1.0 - sinT2);
  float rs = (c - mu * cosT) / (c + mu * cosT);
  float rp = (mu * c - cosT) / (mu * c + cosT);
  return 0.5 * (rs * rs + rp * rp);
}

// Bragg-Snell wavelength of order k for FCC (111) planes of spacing d, with
// sinGlancing the sine of the angle between the light and the lattice plane:
// lambda = 2 d sqrt(mu^2 - cos^2 theta1) / k (eq. 4 with Snell's law at the
// plane); k = 1 spans [lambdaMin, lambdaMax] of eq. 5.
float braggSnellWavelength(float planeSpacing, float mu, float sinGlancing, int order)
{
  float cos2 = 1.0 - sinGlancing * sinGlancing;
  return 2.0 * planeSpacing * sqrt(max(mu * mu - cos2, 0.0)) / float(order);
}

// Average over the bin [centre - width/2, centre + width/2] of a box of peak 1
// and relative full width `bandwidth` around lambdaB: the overlap over the
// bin width, so the result does not depend on the wavelength step.
float braggBandAverage(float binCentre, float binWidth, float lambdaB, float bandwidth)
{
  float lo = max(binCentre - 0.5 * binWidth, lambdaB * (1.0 - 0.5 * bandwidth));
  float hi = min(binCentre + 0.5 * binWidth, lambdaB * (1.0 + 0.5 * bandwidth));
  return max(hi - lo, 0.0) / binWidth;
}

// Gating of the diffraction by the angle between the lattice normal and the
// bisector of the directions to light and eye (a Gaussian of that angle with
// deviation `spread`); spread 0 turns it off, as in the paper.
float mosaicWeight(vec3 latticeNormal, vec3 towardLight, vec3 towardEye, float spread)
{
  if (spread <= 0.0)
  {
    return 1.0;
  }
  vec3 bisector = normalize(towardLight + towardEye);
  float angle = acos(clamp(abs(dot(latticeNormal, bisector)), 0.0, 1.0));
  return exp(-0.5 * (angle / spread) * (angle / spread));
}
