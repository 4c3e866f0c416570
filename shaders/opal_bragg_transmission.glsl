// What a diffraction domain passes of light crossing it, per wavelength bin
// (docs/design.md §7.2): 1 - R of every plane family and order in the
// coupled-wave model, 1 - B of the paper's box band. Shared by the view march
// (the view ray's crossings, the light's Bragg shadows) and the Bragg shadow
// table (the light's transmittance per domain). The including pass declares
// WAVELENGTHS and COUPLED_WAVE and includes opal_optics.glsl and
// opal_coupled_wave.glsl first.

// What one domain passes per bin, the product of its 1 - R(lambda)
// (passThroughDomain): the light's Bragg shadow, or the view ray's crossing.
float passed[WAVELENGTHS];

// Family f of the domain at order k, its unit normal in the model frame
// `normal`, for a ray of unit direction `ray`: its period, coupling and
// coherent thickness, the crystal being thicknessMm thick along the normal
// (docs/design.md §7.2).
CoupledWaveFamily coupledFamily(DomainRecord lattice, vec3 normal, int f, int k, vec3 ray, float thicknessMm)
{
  float squaredMiller = dot(FCC_MILLER[f], FCC_MILLER[f]);
  float spacing = lattice.planeSpacing * sqrt(3.0 / squaredMiller); // d_hkl = a / sqrt(h^2 + k^2 + l^2)
  // x = pi D / d_hkl, D = d_111 sqrt(3/2).
  float x = OPAL_PI * sqrt(1.5) * lattice.planeSpacing / spacing;
  float layers = min(thicknessMm * 1e6 / spacing, P.coherentLayers);
  return coupledWaveFamily(abs(dot(ray, normal)), spacing / float(k),
    abs(P.permittivityContrast * sphereFormFactor(float(k) * x)), layers * spacing);
}

// The unit normal of family f in the model frame.
vec3 familyNormal(DomainRecord lattice, int f)
{
  return f == 0 ? lattice.latticeNormal : rotateByQuaternion(lattice.orientation, normalize(FCC_MILLER[f]));
}

// The short edge of the first bin: no order's lambda_B below it reaches a bin.
float shortestWavelength()
{
  return bins[0].lambda - 0.5 * bins[0].width;
}

// The first and last bin overlapping the wavelengths [window.x, window.y]
// (the bins are one step wide, each beside the next: §3.6), so a narrow
// window loops over its few bins only.
ivec2 binsWithin(vec2 window)
{
  float start = shortestWavelength(), step = bins[0].width;
  int first = max(int(ceil((window.x - start) / step)) - 1, 0);
  int last = min(int(floor((window.y - start) / step)), WAVELENGTHS - 1);
  return ivec2(first, last);
}

// The centre of bin l: the bins are one step wide, each beside the next
// (§3.6), so no per-lane load of the table where lanes loop over other bins.
float binCentre(int l)
{
  return bins[0].lambda + float(l) * bins[0].width;
}

// The bins of family f's window (x, y) and those among them that may need
// coupledWaveBinAverage's band forms (z, w: those overlapping the band's
// wavelengths widened by 1e-4 lambda_B, far beyond float rounding); the rest
// take coupledWaveWingAverage, the same value without the band's forms,
// which every SIMD lane would otherwise evaluate (docs/design.md §7.2).
ivec4 coupledWaveBins(CoupledWaveFamily f)
{
  float shortest = shortestWavelength();
  ivec2 band = binsWithin(coupledWaveBand(f, shortest) + vec2(-1e-4, 1e-4) * f.braggWavelength);
  ivec2 window = binsWithin(coupledWaveWindow(f));
  return ivec4(window, max(band.x, window.x), min(band.y, window.y));
}

// R of family f in bin l, a wing bin of coupledWaveBins; bandBin: any bin.
float wingBin(CoupledWaveFamily f, int l)
{
  return coupledWaveWingAverage(f, binCentre(l), bins[0].width);
}

float bandBin(CoupledWaveFamily f, int l)
{
  return coupledWaveBinAverage(f, binCentre(l), bins[0].width);
}

// What passes the domain keeps 1 - R of the family and order.
void transmitFamily(CoupledWaveFamily family)
{
  ivec4 range = coupledWaveBins(family);
  for (int l = range.x; l <= range.y; ++l)
  {
    if (l < range.z || l > range.w) passed[l] *= 1.0 - wingBin(family, l);
  }
  for (int l = range.z; l <= range.w; ++l)
  {
    passed[l] *= 1.0 - bandBin(family, l);
  }
}

// What a ray of unit direction `ray` keeps per bin after lengthMm of it in a
// domain (docs/design.md §7.2), into `passed`: 1 - R of every family and
// order in the coupled-wave model; 1 - B of each order's box band in the
// paper's (R = B: the band reflects all the light within it).
void passThroughDomain(DomainRecord lattice, vec3 ray, float lengthMm)
{
  for (int l = 0; l < WAVELENGTHS; ++l) passed[l] = 1.0;
  if (!COUPLED_WAVE)
  {
    float sinGlancing = abs(dot(ray, lattice.latticeNormal));
    for (int k = 1; k <= P.braggOrders; ++k)
    {
      float lambdaB = braggSnellWavelength(lattice.planeSpacing, P.refractiveIndex, sinGlancing, k);
      for (int l = 0; l < WAVELENGTHS; ++l)
      {
        passed[l] *= 1.0 - braggBandAverage(bins[l].lambda, bins[l].width, lambdaB, P.braggBandwidth);
      }
    }
    return;
  }
  float shortest = shortestWavelength();
  for (int f = 0; f < P.latticeFamilies; ++f)
  {
    vec3 normal = familyNormal(lattice, f);
    // The crystal's thickness along the normal: the ray's path in the domain
    // projected on it (a slab's thickness for planes parallel to it).
    float thicknessMm = lengthMm * abs(dot(ray, normal));
    for (int k = 1; k <= 64; ++k)
    {
      CoupledWaveFamily family = coupledFamily(lattice, normal, f, k, ray, thicknessMm);
      if (family.braggWavelength < shortest) break;
      transmitFamily(family);
    }
  }
}
