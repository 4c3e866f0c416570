// The device's limits as a GPU's would bind them, simulated on lavapipe
// (VulkanOptions::Simulated, docs/design.md §3.7): with at most eight
// workgroups per dispatch along x (the least a march tile needs), every
// one-dimensional pass, direct or a queue's indirect dispatch, goes as a grid
// of rows of eight groups; the images are identical to those of the device's own limits for
// the light from above (the layer sweep and its queues, the highlight's
// queue), from the side (the per-voxel march) and with energy conservation
// (the Bragg shadow table), and the validation layer is silent. With a
// storage-buffer range of 128 KiB, a volume whose fields exceed it is read
// through its fields' device addresses, with the same images (every order
// of scattering and absorption too). A device whose workgroups cannot hold a
// pass's is refused at start-up naming the limit.
#include "OpalRenderScenes.h"
#include "OpalTestHarness.h"
#include "OpalVolumeBuild.h"
#include "OpalVulkanError.h"

#include <string>
#include <vector>

namespace
{
struct Scene
{
  std::string Name;
  opal::RenderParameters Parameters;
};

std::vector<Scene> scenes()
{
  opal::RenderParameters above;
  above.ImageSize = { 160, 120 }; // the highlight's select pass 300 groups, its queue over 8
  opal::RenderParameters side = above;
  side.LightPosition = { 60.0, 10.0, 0.0 };
  opal::RenderParameters conserving = above;
  conserving.BraggModel = opal::BraggModelKind::CoupledWave;
  conserving.EnergyConservation = true;
  return { { "light above", above }, { "light to the side", side }, { "energy conservation", conserving } };
}

opal::VulkanOptions withValidation()
{
  opal::VulkanOptions options;
  options.Validation = true;
  return options;
}

void checkSplitDispatches(const opal::RenderVolume& volume)
{
  opaltest::SceneRenderer own(withValidation());
  opal::VulkanOptions eightGroups = withValidation();
  eightGroups.Simulated.MaxComputeWorkGroupCount = 8;
  opaltest::SceneRenderer simulated(eightGroups);
  for (const Scene& scene : scenes())
  {
    const opal::RenderImage a = own.render(volume, scene.Parameters), b = simulated.render(volume, scene.Parameters);
    OPAL_CHECK(opaltest::identical(a, b), scene.Name + ": eight workgroups per dispatch give the device's image");
  }
  for (opaltest::SceneRenderer* renderer : { &own, &simulated })
  {
    const auto messages = renderer->context().validationMessages();
    OPAL_CHECK(messages.empty(), "the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
  }
}

// Fields beyond the storage-buffer range, read through their addresses.
void checkAddressedFields(const opal::RenderVolume& volume, const opal::RenderVolume& absorbing)
{
  opaltest::SceneRenderer own(withValidation());
  opal::VulkanOptions smallRange = withValidation();
  smallRange.Simulated.MaxStorageBufferRange = 128 << 10; // the cells' 320 KB exceed it, 48 x 36 pixels do not
  opaltest::SceneRenderer addressed(smallRange);
  std::vector<Scene> cases = scenes();
  opal::RenderParameters everyOrder = cases.front().Parameters;
  everyOrder.ScatteringOrders = opal::ScatteringOrdersKind::All;
  everyOrder.ScatteringPhotons = 4096;
  cases.push_back({ "every order", everyOrder });
  for (Scene& scene : cases)
  {
    scene.Parameters.ImageSize = { 48, 36 };
    OPAL_CHECK(opaltest::identical(own.render(volume, scene.Parameters), addressed.render(volume, scene.Parameters)),
      scene.Name + ": fields read through their addresses give the bound fields' image");
  }
  OPAL_CHECK(opaltest::identical(own.render(absorbing, cases.front().Parameters), addressed.render(absorbing, cases.front().Parameters)),
    "an absorbing volume: fields read through their addresses give the bound fields' image");
  const auto messages = addressed.context().validationMessages();
  OPAL_CHECK(messages.empty(), "the validation layer is silent" + (messages.empty() ? "" : ": " + messages.front()));
}

void checkSmallWorkgroupsRefused()
{
  opal::VulkanOptions small = withValidation();
  small.Simulated.MaxComputeWorkGroupInvocations = 128; // the light pass runs 256
  std::string message;
  try
  {
    opaltest::SceneRenderer refused(small);
  }
  catch (const opal::VulkanError& e)
  {
    message = e.what();
  }
  OPAL_CHECK(message.find("maxComputeWorkGroupInvocations 128") != std::string::npos &&
      message.find("light pass") != std::string::npos,
    "workgroups of 128 invocations are refused at start-up naming the limit (got: " + message + ")");
}
} // namespace

int TestOpalDeviceLimits(int, char*[])
{
  if (!opaltest::makeRenderer())
  {
    return opaltest::noDeviceReturnCode();
  }
  opal::ModelParameters model;
  model.Dimensions = { 40, 20, 50 };
  const auto volume = opal::buildVolume(model);
  checkSplitDispatches(volume->renderVolume());
  model.BackingThickness = 1.0; // an absorbing backing layer (docs/design.md §2.10)
  model.BackingAbsorption = 2.0;
  const auto absorbing = opal::buildVolume(model);
  checkAddressedFields(volume->renderVolume(), absorbing->renderVolume());
  checkSmallWorkgroupsRefused();
  return opaltest::finish("TestOpalDeviceLimits");
}
