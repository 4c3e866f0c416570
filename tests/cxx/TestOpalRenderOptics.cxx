// The render's optics against closed forms, on synthetic slab scenes (on
// lavapipe where there is no GPU), with the Vulkan validation layer on:
// Fresnel at normal incidence, D65 to sRGB white, the Bragg-Snell wavelength
// over tilt angles (lambda_max at normal incidence, lambda_min at grazing), a
// flat domain's spectrum peaking at lambda_max, the transmittance of a
// homogeneous slab, monochromatic hues, and no ray tunnelling through a
// one-voxel-thick tilted domain; an index-matched boundary and a flat
// illuminant; a homogeneous slab against single scattering's closed form
// (its lambda^-4 colour, the 1/r^2 fall-off over light heights, the Fresnel
// transmission at the light's oblique entry); an absorbing slab's
// transmittance exp(-mu_a (550/lambda)^p L) and its body against the closed
// form with absorption (docs/design.md §3.9).
#include "OpalOptics.h"
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <cstdint>
#include <string>
#include <tuple>

namespace
{
constexpr double Mu = 1.45;
constexpr int Centre = 16; // the centre pixel of slabView's 33 x 33
constexpr double LambdaMaxPlaneSpacing = 600.0 / (2.0 * Mu); // lambda_max = 600 nm

using opaltest::SceneRenderer;
using opaltest::SlabScene;

void checkRender(SceneRenderer& renderer, const opal::RenderImage& image, const std::string& what)
{
  OPAL_CHECK(opaltest::allFinite(image), what + ": no NaN or Inf in any output");
  const auto messages = renderer.context().validationMessages();
  OPAL_CHECK(messages.empty(), what + ": the validation layer is silent" +
      (messages.empty() ? std::string() : ", first message: " + messages.front()));
}

// Renders the scene and checks the render itself (finite, validation layer silent).
opal::RenderImage renderChecked(
  SceneRenderer& renderer, SlabScene& scene, const opal::RenderParameters& p, const std::string& what)
{
  opal::RenderImage image = renderer.render(scene.build(), p);
  checkRender(renderer, image, what);
  return image;
}

// A slab with one domain of the given (111) plane spacing, by default flat at its centre.
SlabScene domainScene(double planeSpacing)
{
  SlabScene scene;
  scene.WithDomain = true;
  scene.PlaneSpacing = planeSpacing;
  return scene;
}

// A slab with one square domain at its centre, its normal tilted by
// `tiltDegrees` from +y towards +x.
SlabScene tiltedDomainScene(double planeSpacing, double tiltDegrees, double halfSize)
{
  SlabScene scene = domainScene(planeSpacing);
  const double tilt = tiltDegrees * opal::Pi / 180.0;
  scene.DomainNormal = glm::dvec3(std::sin(tilt), std::cos(tilt), 0.0);
  scene.DomainCentre = glm::dvec3(0.0, 1.0, 0.0);
  scene.DomainHalfSize = halfSize;
  return scene;
}

// The paper's set-up over the slab with the opal's refractive index Mu.
opal::RenderParameters opalView()
{
  opal::RenderParameters p = opaltest::slabView();
  p.RefractiveIndex = Mu;
  return p;
}

// The camera of slabView: direction of the ray through pixel centre (x, y).
glm::dvec3 pixelDirection(const opal::RenderParameters& p, double x, double y)
{
  const double tanHalf = std::tan(p.ViewAngle * opal::Pi / 360.0);
  const double nx = 2.0 * x / p.ImageSize[0] - 1.0, ny = 1.0 - 2.0 * y / p.ImageSize[1];
  const glm::dvec3 forward(0, -1, 0), up(0, 0, -1);
  const glm::dvec3 right = glm::cross(forward, up);
  return glm::normalize(forward + nx * tanHalf * (double(p.ImageSize[0]) / p.ImageSize[1]) * right + ny * tanHalf * up);
}

// Fresnel at normal incidence, and the highlight's D65 spectrum as sRGB white.
void checkHighlight(SceneRenderer& renderer)
{
  SlabScene scene;
  opal::RenderParameters p = opaltest::slabView();
  p.LightRadius = 2.0;
  p.RefractiveIndex = Mu;
  const opal::RenderImage image = renderChecked(renderer, scene, p, "highlight");
  const std::size_t i = opaltest::pixelIndex(image, Centre, Centre);
  const double lightRadiance = 28.0 * 28.0 / (opal::Pi * 2.0 * 2.0);
  const double fresnel = image.XYZ[3 * i + 1] / lightRadiance;
  const double expected = std::pow((Mu - 1) / (Mu + 1), 2);
  OPAL_CHECK(std::fabs(fresnel - expected) < 0.01 * expected,
    "Fresnel at normal incidence " + std::to_string(fresnel) + " = ((mu-1)/(mu+1))^2 = " + std::to_string(expected));
  const float* rgb = &image.Radiance[3 * i];
  const double mean = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
  OPAL_CHECK(std::fabs(rgb[0] - mean) < 0.01 * mean && std::fabs(rgb[1] - mean) < 0.01 * mean &&
      std::fabs(rgb[2] - mean) < 0.01 * mean,
    "D65 maps to sRGB white within 1%: " + std::to_string(rgb[0]) + " " + std::to_string(rgb[1]) + " " +
      std::to_string(rgb[2]));
}

// The validation settings: an index-matched boundary (mu = 1) reflects
// nothing; with Illuminant none the highlight's spectrum is flat, the
// Fresnel reflectance times the light's radiance at every wavelength.
void checkValidationSettings(SceneRenderer& renderer)
{
  SlabScene scene;
  opal::RenderParameters p = opaltest::slabView();
  p.LightRadius = 2.0;
  p.RefractiveIndex = 1.0;
  opal::RenderImage image = renderChecked(renderer, scene, p, "index-matched");
  const std::size_t i = opaltest::pixelIndex(image, Centre, Centre);
  OPAL_CHECK(image.XYZ[3 * i + 1] == 0.0f, "an index-matched boundary shows no highlight, got Y " +
      std::to_string(image.XYZ[3 * i + 1]));
  p.RefractiveIndex = Mu;
  p.Illuminant = opal::LightSpectrum::None;
  p.WriteSpectrum = true;
  image = renderChecked(renderer, scene, p, "illuminant none");
  const double expected = std::pow((Mu - 1) / (Mu + 1), 2) * 28.0 * 28.0 / (opal::Pi * 2.0 * 2.0);
  const std::size_t n = image.Wavelengths.size();
  double worst = 0;
  for (std::size_t l = 0; l < n; ++l)
  {
    worst = std::max(worst, std::fabs(image.Spectrum[i * n + l] / expected - 1));
  }
  OPAL_CHECK(worst < 0.01 && image.Illuminant == "none" && image.IlluminantScale == 1.0,
    "Illuminant none: the highlight's spectrum is F x the light's radiance at every wavelength, worst " +
      std::to_string(100 * worst) + "%");
}

// The light straight above the domain's centre: glancing angle 90 deg - tilt.
void checkBraggSnellAt(SceneRenderer& renderer, double tilt)
{
  SlabScene scene = tiltedDomainScene(LambdaMaxPlaneSpacing, tilt, 0.8);
  const opal::RenderImage image = renderChecked(renderer, scene, opalView(), "tilt " + std::to_string(tilt));
  const double sinTilt = std::sin(tilt * opal::Pi / 180.0);
  const double expected = 2.0 * LambdaMaxPlaneSpacing * std::sqrt(Mu * Mu - sinTilt * sinTilt);
  const double got = image.DominantBraggWavelength[opaltest::pixelIndex(image, Centre, Centre)];
  OPAL_CHECK(std::fabs(got - expected) < 0.002 * expected,
    "Bragg-Snell wavelength at tilt " + std::to_string(tilt) + ": " + std::to_string(got) + " nm, closed form " +
      std::to_string(expected));
  if (tilt == 0.0)
  {
    OPAL_CHECK(std::fabs(got - 600.0) < 0.6, "normal incidence gives lambda_max = 2 mu d");
  }
  if (tilt == 89.5)
  {
    const double lambdaMin = 600.0 * std::sqrt(1.0 - 1.0 / (Mu * Mu));
    OPAL_CHECK(std::fabs(got - lambdaMin) < 0.002 * lambdaMin, "grazing incidence gives lambda_min (eq. 5)");
  }
}

void checkBraggSnell(SceneRenderer& renderer)
{
  for (double tilt : { 0.0, 20.0, 40.0, 60.0, 80.0, 89.5 })
  {
    checkBraggSnellAt(renderer, tilt);
  }
}

// A flat domain: the spectrum of a pixel above it peaks at lambda_max.
void checkFlatDomainSpectrum(SceneRenderer& renderer)
{
  SlabScene scene = domainScene(LambdaMaxPlaneSpacing);
  opal::RenderParameters p = opalView();
  p.WriteSpectrum = true;
  const opal::RenderImage image = renderChecked(renderer, scene, p, "flat domain");
  const std::size_t pixel = opaltest::pixelIndex(image, Centre + 5, Centre - 4);
  const std::size_t n = image.Wavelengths.size();
  std::size_t peak = 0;
  for (std::size_t l = 0; l < n; ++l)
  {
    if (image.Spectrum[pixel * n + l] > image.Spectrum[pixel * n + peak])
    {
      peak = l;
    }
  }
  OPAL_CHECK(std::fabs(image.Wavelengths[peak] - 600.0) <= 10.0,
    "spectrum above a flat domain peaks at lambda_max 600 nm, got " + std::to_string(image.Wavelengths[peak]));
}

// The transmittance slab: scattering `scattering` and absorption
// `absorption` (exponent p) everywhere, the domain's light scaled by `gain`.
opal::RenderImage renderSlab(SceneRenderer& renderer, const opal::RenderParameters& p, double scattering, bool domain,
  double gain, double absorption = 0.0, double exponent = 0.0)
{
  SlabScene scene;
  scene.Scattering = scattering;
  scene.Absorption = absorption;
  scene.AbsorptionExponent = exponent;
  scene.WithDomain = domain;
  scene.DomainCentre = glm::dvec3(0.0, 0.95, 0.0); // the voxel layer of cells [0.9, 1.0)
  scene.PlaneSpacing = LambdaMaxPlaneSpacing;
  opal::RenderParameters q = p;
  q.DiffractionGain = gain;
  return renderChecked(renderer, scene, q, "slab");
}

// The light and view paths through the slab, from the top (y = 2) down by
// `depth` (1: to the domain voxel's top, y = 1), of the ray through pixel (px, py).
double slabPathLength(const opal::RenderParameters& p, int px, int py, double depth = 1.0)
{
  const glm::dvec3 view = pixelDirection(p, px + 0.5, py + 0.5);
  const glm::dvec3 refracted = glm::refract(view, glm::dvec3(0, 1, 0), 1.0 / Mu);
  const double viewPath = depth / -refracted.y;
  const glm::dvec3 atDomain = glm::dvec3(0, 30, 0) + (28.0 / -view.y) * view + viewPath * refracted;
  const double lightPath = depth / glm::normalize(glm::dvec3(0, 30, 0) - atDomain).y;
  return viewPath + lightPath;
}

// Transmittance of a homogeneous slab: the domain's light, less the body's
// own scattering, is the clear-slab domain light times exp(-tau(lambda)).
void checkSlabTransmittance(SceneRenderer& renderer)
{
  const double mus = 0.3;
  opal::RenderParameters p = opalView();
  p.WriteSpectrum = true;
  const opal::RenderImage both = renderSlab(renderer, p, mus, true, 4.0);
  const opal::RenderImage bodyOnly = renderSlab(renderer, p, mus, true, 0.0);
  const opal::RenderImage clear = renderSlab(renderer, p, 0.0, true, 4.0);
  const int px = Centre + 3, py = Centre;
  const std::size_t pixel = opaltest::pixelIndex(both, px, py);
  const double path = slabPathLength(p, px, py);
  const std::size_t n = both.Wavelengths.size();
  const float* clearSpectrum = &clear.Spectrum[pixel * n];
  double worst = 0;
  for (std::size_t l = 0; l < n; ++l)
  {
    const double clearValue = clearSpectrum[l];
    if (clearValue <= 0.5 * *std::max_element(clearSpectrum, clearSpectrum + n))
    {
      continue; // outside the band's flat top
    }
    const double ratio = (both.Spectrum[pixel * n + l] - bodyOnly.Spectrum[pixel * n + l]) / clearValue;
    const double s = std::pow(550.0 / both.Wavelengths[l], 4.0);
    const double expected = std::exp(-mus * s * path);
    worst = std::max(worst, std::fabs(ratio - expected) / expected);
  }
  OPAL_CHECK(worst < 0.02, "slab transmittance equals exp(-tau) within 2%, worst " + std::to_string(worst));
}

// An absorbing, non-scattering slab: the domain's light is the clear slab's
// times exp(-mu_a (550/lambda)^p L) over the light and view paths L to the
// middle of the domain's voxel layer (the domain absorbs too; its crossing
// is taken there, docs/design.md §3.4), grey (p = 0) and coloured (p = 4
// and -2).
void checkAbsorbingSlab(SceneRenderer& renderer)
{
  const double mua = 0.4;
  opal::RenderParameters p = opalView();
  p.WriteSpectrum = true;
  const opal::RenderImage clear = renderSlab(renderer, p, 0.0, true, 4.0);
  const int px = Centre + 3, py = Centre;
  const std::size_t pixel = opaltest::pixelIndex(clear, px, py), n = clear.Wavelengths.size();
  const double path = slabPathLength(p, px, py, 1.05);
  const float* clearSpectrum = &clear.Spectrum[pixel * n];
  for (double exponent : { 0.0, 4.0, -2.0 })
  {
    const opal::RenderImage absorbing = renderSlab(renderer, p, 0.0, true, 4.0, mua, exponent);
    double worst = 0;
    int compared = 0;
    for (std::size_t l = 0; l < n; ++l)
    {
      if (clearSpectrum[l] <= 0.5 * *std::max_element(clearSpectrum, clearSpectrum + n))
      {
        continue; // outside the band's flat top
      }
      const double expected = std::exp(-mua * std::pow(550.0 / clear.Wavelengths[l], exponent) * path);
      worst = std::max(worst, std::fabs(absorbing.Spectrum[pixel * n + l] / clearSpectrum[l] / expected - 1));
      ++compared;
    }
    OPAL_CHECK(compared >= 2 && worst < 0.01, "absorbing slab, p = " + std::to_string(exponent) +
        ": transmittance exp(-mu_a (550/lambda)^p L) within 1% at " + std::to_string(compared) +
        " wavelengths, worst " + std::to_string(worst));
  }
}

// Unpolarised Fresnel reflectance of a dielectric of index mu at incidence
// cosine c (the test's own, from the textbook formula).
double fresnelClosedForm(double c, double mu)
{
  const double sinT2 = (1 - c * c) / (mu * mu);
  if (sinT2 >= 1)
    return 1;
  const double t = std::sqrt(1 - sinT2);
  const double rs = (c - mu * t) / (c + mu * t), rp = (mu * c - t) / (mu * c + t);
  return 0.5 * (rs * rs + rp * rp);
}

// The body against the closed form of single scattering: a homogeneous
// Rayleigh slab (mu_s(550) 0.3/mm, 2 mm thick, top at y = 2), seen straight
// down at its centre, lit by a point light at L (unit spectral irradiance at
// the apex, the top's centre). Along the centre column x = (0, 2 - z, 0):
//   L(lambda) = (1 - F(1)) mu_s s/(4 pi) * integral_0^H T(cos_L) |L - apex|^2 / |L - x|^2
//               * exp(-mu_s s (z / cos_L + z)) dz,
// s = (550/lambda)^4, cos_L the light direction's y at x (the path to the
// light is straight, docs/design.md §3: it enters the top at incidence cos_L
// and crosses z / cos_L of the slab), T = 1 - F its Fresnel transmission;
// by Simpson's rule on 20000 intervals (converged far below the tolerance),
// independently of the render's voxel sampling.
double slabSingleScattering(double mus, double s, const glm::dvec3& light, double mu, double mua = 0.0)
{
  const int intervals = 20000;
  const double thickness = 2.0, h = thickness / intervals;
  const glm::dvec3 apex(0, 2, 0);
  const double apexDistance2 = glm::dot(light - apex, light - apex);
  double sum = 0;
  for (int k = 0; k <= intervals; ++k)
  {
    const double z = k * h;
    const glm::dvec3 x(0, 2 - z, 0);
    const double r2 = glm::dot(light - x, light - x), cosL = (light.y - x.y) / std::sqrt(r2);
    const double f =
      (1 - fresnelClosedForm(cosL, mu)) * apexDistance2 / r2 * std::exp(-(mus * s + mua) * (z / cosL + z));
    sum += f * (k == 0 || k == intervals ? 1.0 : (k % 2 ? 4.0 : 2.0));
  }
  return (1 - fresnelClosedForm(1, mu)) * mus * s / (4.0 * opal::Pi) * sum * h / 3.0;
}

// The centre pixel's spectrum against the closed form, worst relative
// difference; the slab absorbs `absorption` with exponent p, the march on
// `nodes` spectral nodes (0: every wavelength).
double bodyAgainstClosedForm(SceneRenderer& renderer, const glm::dvec3& light, double mu, const std::string& what,
  double absorption = 0.0, double exponent = 0.0, int nodes = 0)
{
  SlabScene scene;
  scene.Scattering = 0.3;
  scene.Absorption = absorption;
  scene.AbsorptionExponent = exponent;
  opal::RenderParameters p = opaltest::slabView();
  p.LightPosition = { light.x, light.y, light.z };
  p.RefractiveIndex = mu;
  p.Illuminant = opal::LightSpectrum::None;
  p.SpectralNodes = nodes;
  p.WriteSpectrum = true;
  p.LightRadius = 0.01; // its highlight far from the centre pixel
  const opal::RenderImage image = renderChecked(renderer, scene, p, what);
  const std::size_t pixel = opaltest::pixelIndex(image, Centre, Centre), n = image.Wavelengths.size();
  double worst = 0;
  for (std::size_t l = 0; l < n; ++l)
  {
    const double s = std::pow(550.0 / image.Wavelengths[l], 4.0);
    const double mua = absorption * std::pow(550.0 / image.Wavelengths[l], exponent);
    const double expected = slabSingleScattering(scene.Scattering, s, light, mu, mua);
    worst = std::max(worst, std::fabs(image.Spectrum[pixel * n + l] / expected - 1));
  }
  std::cout << what << ": homogeneous slab against single scattering's closed form: worst " << 100 * worst << "%"
            << std::endl;
  return worst;
}

// Behind an index-matched boundary, lit from straight above: the lambda^-4
// colour and the 1/r^2 fall-off on the axis, the light 3, 28 and 98 mm above
// the top (the fall-off over the 2 mm slab from 56% to 4%). Then the Fresnel
// transmission at an oblique entry of the light, mu = 1.45, the light 28 mm
// from the apex at 30 and 60 degrees from the vertical (the light's path
// through the slab 1.15 and 2 times the depth). The march's midpoint
// sub-steps err by about (tau per step)^2 / 24: measured 0.24-0.37% from
// above (tolerance 0.5%), 0.46% and 0.88% at 30 and 60 degrees, where at
// 380 nm a 0.1 mm step crosses an optical depth of 0.4 (tolerance 1%).
void checkBodyClosedForm(SceneRenderer& renderer)
{
  for (double height : { 3.0, 28.0, 98.0 })
  {
    const std::string what = "index-matched, light " + std::to_string(static_cast<int>(height)) + " mm above";
    OPAL_CHECK(bodyAgainstClosedForm(renderer, glm::dvec3(0, 2 + height, 0), 1.0, what) < 0.005,
      what + ": within 0.5% of the closed form at every wavelength (its lambda^-4 colour and 1/r^2 fall-off)");
  }
  for (double degrees : { 30.0, 60.0 })
  {
    const double angle = degrees * opal::Pi / 180.0;
    const std::string what = "mu 1.45, light at " + std::to_string(static_cast<int>(degrees)) + " degrees";
    const glm::dvec3 light(28.0 * std::sin(angle), 2 + 28.0 * std::cos(angle), 0);
    OPAL_CHECK(bodyAgainstClosedForm(renderer, light, Mu, what) < 0.01,
      what + ": within 1% of the closed form with the Fresnel transmission at the light's oblique entry");
  }
}

// The body of an absorbing slab against the closed form, with mu_t = mu_s +
// mu_a on both paths: grey and coloured absorption (p = 2), every wavelength
// and on the 16 spectral nodes; the light 28 mm from the apex at 30 degrees
// (its highlight away from the centre pixel). As in checkBodyClosedForm the
// midpoint sub-steps err by about (tau per step)^2 / 24, here larger: at
// 380 nm mu_t = 1.3 + 1.05 (p = 2) per mm; measured 0.76% grey, 1.21% with
// p = 2 (tolerance 1.5%).
void checkAbsorbingBody(SceneRenderer& renderer)
{
  const double angle = 30.0 * opal::Pi / 180.0;
  const glm::dvec3 light(28.0 * std::sin(angle), 2 + 28.0 * std::cos(angle), 0);
  for (const auto& [exponent, nodes] : { std::pair<double, int>{ 0.0, 0 }, { 2.0, 0 }, { 2.0, 16 } })
  {
    const std::string what = "absorbing slab (0.5/mm, p " + std::to_string(exponent) + ", " +
      std::to_string(nodes) + " nodes)";
    OPAL_CHECK(bodyAgainstClosedForm(renderer, light, Mu, what, 0.5, exponent, nodes) < 0.015,
      what + ": the body within 1.5% of the closed form with absorption on both paths");
  }
}

void checkHue(SceneRenderer& renderer, double lambda, int channel, const char* name)
{
  SlabScene scene = domainScene(lambda / (2.0 * Mu));
  opal::RenderParameters p = opalView();
  p.BraggBandwidth = 0.01;
  p.Exposure = 0.5;
  const opal::RenderImage image = renderChecked(renderer, scene, p, name);
  const std::size_t pixel = opaltest::pixelIndex(image, Centre + 5, Centre + 5);
  const std::uint8_t* rgb = &image.RGB[3 * pixel];
  const int strongest = static_cast<int>(std::max_element(rgb, rgb + 3) - rgb);
  OPAL_CHECK(strongest == channel && rgb[channel] > 0,
    std::to_string(static_cast<int>(lambda)) + " nm looks " + name + ": RGB " + std::to_string(rgb[0]) + " " +
      std::to_string(rgb[1]) + " " + std::to_string(rgb[2]));
}

void checkMonochromaticHues(SceneRenderer& renderer)
{
  for (const auto& [lambda, channel, name] : { std::tuple<double, int, const char*>{ 450.0, 2, "blue" },
         { 550.0, 1, "green" }, { 650.0, 0, "red" } })
  {
    checkHue(renderer, lambda, channel, name);
  }
}

// Pixels whose straight ray crosses the domain's plane well inside its square
// edges, how many of those miss the domain, and how many well outside hit it.
struct DomainCoverage
{
  int Inside = 0, Holes = 0, Strays = 0;
};

DomainCoverage domainCoverage(const opal::RenderImage& image, const opal::RenderParameters& p, const SlabScene& scene)
{
  const glm::dvec3 n = glm::normalize(scene.DomainNormal);
  const glm::dvec3 u = glm::normalize(glm::cross(n, glm::dvec3(0, 1, 0)));
  const glm::dvec3 v = glm::cross(n, u);
  const double margin = 0.1 * std::sqrt(3.0); // a voxel's diagonal
  DomainCoverage coverage;
  for (int y = 0; y < p.ImageSize[1]; ++y)
  {
    for (int x = 0; x < p.ImageSize[0]; ++x)
    {
      const glm::dvec3 d = pixelDirection(p, x + 0.5, y + 0.5);
      const glm::dvec3 eye(0, 30, 0);
      const double t = glm::dot(scene.DomainCentre - eye, n) / glm::dot(d, n);
      const glm::dvec3 local = eye + t * d - scene.DomainCentre;
      const double edge = std::max(std::fabs(glm::dot(local, u)), std::fabs(glm::dot(local, v)));
      const bool registered = image.DominantBraggWavelength[opaltest::pixelIndex(image, x, y)] > 0;
      if (edge < scene.DomainHalfSize - margin)
      {
        ++coverage.Inside;
        coverage.Holes += registered ? 0 : 1;
      }
      else if (edge > scene.DomainHalfSize + margin)
      {
        coverage.Strays += registered ? 1 : 0;
      }
    }
  }
  return coverage;
}

// No tunnelling: with mu ~ 1 the rays run straight; every ray whose line
// crosses the tilted polygon well inside its edges registers the domain,
// and none well outside does.
void checkNoTunnelling(SceneRenderer& renderer)
{
  SlabScene scene = tiltedDomainScene(330.0, 35.0, 1.0);
  opal::RenderParameters p = opaltest::slabView(61);
  p.RefractiveIndex = 1.0001;
  const opal::RenderImage image = renderChecked(renderer, scene, p, "tunnelling");
  const DomainCoverage coverage = domainCoverage(image, p, scene);
  OPAL_CHECK(coverage.Inside > 100, "the tilted domain covers many pixels: " + std::to_string(coverage.Inside));
  OPAL_CHECK(coverage.Holes == 0, std::to_string(coverage.Holes) + " rays tunnelled through the domain");
  OPAL_CHECK(coverage.Strays == 0, std::to_string(coverage.Strays) + " rays registered the domain outside it");
}
} // namespace

int TestOpalRenderOptics(int, char*[])
{
  auto renderer = opaltest::makeRenderer();
  if (!renderer)
  {
    return opaltest::noDeviceReturnCode();
  }
  checkHighlight(*renderer);
  checkValidationSettings(*renderer);
  checkBraggSnell(*renderer);
  checkFlatDomainSpectrum(*renderer);
  checkSlabTransmittance(*renderer);
  checkBodyClosedForm(*renderer);
  checkAbsorbingSlab(*renderer);
  checkAbsorbingBody(*renderer);
  checkMonochromaticHues(*renderer);
  checkNoTunnelling(*renderer);
  return opaltest::finish("TestOpalRenderOptics");
}
