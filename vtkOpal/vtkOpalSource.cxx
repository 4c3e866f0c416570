#include "vtkOpalSource.h"

#include "OpalRenderFrame.h"

#include "OpalCellBoundaries.h"
#include "OpalDomainLayout.h"
#include "OpalVolumeBuild.h"
#include "OpalModelParameters.h"
#include "OpalOptics.h"
#include "OpalParallel.h"
#include "OpalPresets.h"
#include "OpalRenderParameters.h"
#include "OpalVolumeFiller.h"
#include "vtkOpalFieldData.h"
#include "vtkOpalRankAgreement.h"
#include "vtkOpalSharedVoronoiCells.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataObject.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationDoubleVectorKey.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOpalArrayCopy.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <utility>
#include <optional>
#include <vector>

vtkStandardNewMacro(vtkOpalSource);
namespace
{
// A key the executives copy from input to output in REQUEST_INFORMATION (as
// VTK's data-object meta-data keys are): every filter below the source sees
// the hints, however many pass-through filters lie between.
class vtkOpalDownstreamKey : public vtkInformationDoubleVectorKey
{
public:
  vtkOpalDownstreamKey(const char* name, const char* location, int length)
    : vtkInformationDoubleVectorKey(name, location, length)
  {
  }
  void CopyDefaultInformation(vtkInformation* request, vtkInformation* fromInfo, vtkInformation* toInfo) override
  {
    if (request->Has(vtkStreamingDemandDrivenPipeline::REQUEST_INFORMATION()) && fromInfo->Has(this))
    {
      this->ShallowCopy(fromInfo, toInfo);
    }
  }
};

vtkInformationDoubleVectorKey* renderHintsKey = new vtkOpalDownstreamKey(
  "RENDER_HINTS", "vtkOpalSource", opal::RenderHintsSize);
} // namespace

vtkInformationDoubleVectorKey* vtkOpalSource::RENDER_HINTS()
{
  return renderHintsKey;
}

namespace
{
// Share of the work spent placing domains; filling the voxels takes the rest.
constexpr double LayoutProgressShare = 0.1;
} // namespace

vtkOpalSource::vtkOpalSource()
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
  opal::ModelParameters defaults;
  defaults.applyPreset(opal::DefaultPreset); // the model's defaults are fig12's already
  this->SetModelParameters(defaults);
  this->Preset = opal::DefaultPreset;
  this->SetController(vtkMultiProcessController::GetGlobalController());
}

vtkOpalSource::~vtkOpalSource()
{
  this->SetController(nullptr);
}

vtkCxxSetObjectMacro(vtkOpalSource, Controller, vtkMultiProcessController);

bool vtkOpalSource::SetPresetByName(const char* name)
{
  const int index = name ? opal::presetIndexByName(name) : -1;
  if (index < 0)
  {
    vtkErrorMacro("Preset \"" << (name ? name : "(null)")
                              << "\" is unknown; choose one of: " << opal::presetNameList());
    return false;
  }
  this->SetPreset(index);
  return true;
}

opal::ModelParameters vtkOpalSource::GetModelParameters() const
{
  opal::ModelParameters p;
  OPAL_MODEL_PARAMETERS(OPAL_VTK_TO_STRUCT)
  return p;
}

void vtkOpalSource::SetPreset(int preset)
{
  if (preset == this->Preset)
  {
    return;
  }
  this->Preset = preset;
  opal::ModelParameters p = this->GetModelParameters();
  p.applyPreset(preset); // an unknown index sets nothing; Validate names it
  this->SetModelParameters(p);
}

void vtkOpalSource::SetModelParameters(const opal::ModelParameters& p)
{
  OPAL_MODEL_PARAMETERS(OPAL_VTK_FROM_STRUCT)
  this->Modified();
}

opal::VolumeArrays vtkOpalSource::arrays() const
{
  return this->OutputArrays == RENDER_ARRAYS ? opal::VolumeArrays::Render : opal::VolumeArrays::All;
}

std::string vtkOpalSource::Validate(const int* extent) const
{
  if (this->Preset != opal::CustomPreset && !opal::presetByIndex(this->Preset))
  {
    return "Preset " + std::to_string(this->Preset) + " is unknown; choose one of: " +
      opal::presetNameList() + " (0-" + std::to_string(opal::presets().size()) + ").";
  }
  if (this->OutputArrays != ALL_ARRAYS && this->OutputArrays != RENDER_ARRAYS)
  {
    return "OutputArrays " + std::to_string(this->OutputArrays) + " is unknown; choose all (0) or render (1).";
  }
  const opal::ModelParameters parameters = this->GetModelParameters();
  const std::string error = opal::validate(parameters);
  if (!error.empty() || !extent)
  {
    return error;
  }
  // Refuse what cannot fit in this machine's memory, before any work: the
  // piece asked for, so a volume larger than one machine is built by pieces.
  std::uint64_t voxels = 1;
  for (int a = 0; a < 3; ++a)
  {
    voxels *= static_cast<std::uint64_t>(std::max(extent[2 * a + 1] - extent[2 * a] + 1, 0));
  }
  // An empty request (a rank without a piece) builds nothing.
  return voxels == 0 ? std::string() : opal::volumeMemoryError(parameters, this->arrays(), voxels);
}

bool vtkOpalSource::Refuses(const int* extent)
{
  const std::string error = this->Validate(extent);
  if (!error.empty() && (error != this->ReportedError || this->GetMTime() != this->ReportedErrorTime))
  {
    vtkErrorMacro(<< error);
  }
  this->ReportedError = error;
  this->ReportedErrorTime = this->GetMTime();
  return !error.empty();
}

int vtkOpalSource::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkImageData" : "vtkPolyData");
  return 1;
}

int vtkOpalSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (this->Refuses(nullptr))
  {
    // An empty image, so the executive adds no error of its own about a missing extent.
    const int none[6] = { 0, -1, 0, -1, 0, -1 };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), none, 6);
    return 0;
  }
  const opal::Grid grid = opal::Grid::fromParameters(this->GetModelParameters());
  const int wholeExtent[6] = { 0, grid.Dimensions[0] - 1, 0, grid.Dimensions[1] - 1, 0,
    grid.Dimensions[2] - 1 };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), wholeExtent, 6);
  outInfo->Set(vtkDataObject::SPACING(), grid.Spacing.data(), 3);
  outInfo->Set(vtkDataObject::ORIGIN(), grid.Origin.data(), 3);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  // VoxelType, or with the render's arrays only ScatteringCoefficient (FillVolume).
  vtkDataObject::SetPointDataActiveScalarInfo(
    outInfo, this->OutputArrays == RENDER_ARRAYS ? VTK_FLOAT : VTK_UNSIGNED_CHAR, 1);
  outInfo->Set(RENDER_HINTS(), opal::packHints(opal::renderHints(this->Preset, this->RefractiveIndex)).data(),
    opal::RenderHintsSize);
  return 1;
}

namespace
{
template <typename ArrayT>
vtkNew<ArrayT> makePointArray(const char* name, int components, vtkIdType tuples)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  return array;
}

// The cell data of the domain geometry: each cell's domain's DomainId,
// ParticleDiameter, Normal, BraggLambdaMax and LatticeOrientation (w, x, y, z).
void addDomainCellData(
  vtkPolyData* output, const opal::DomainLayout& layout, const std::vector<int>& cellDomain, double refractiveIndex)
{
  const auto cells = static_cast<vtkIdType>(cellDomain.size());
  auto ids = makePointArray<vtkIntArray>("DomainId", 1, cells);
  auto diameters = makePointArray<vtkFloatArray>("ParticleDiameter", 1, cells);
  auto normals = makePointArray<vtkFloatArray>("Normal", 3, cells);
  auto lambdaMax = makePointArray<vtkFloatArray>("BraggLambdaMax", 1, cells);
  auto orientations = makePointArray<vtkFloatArray>("LatticeOrientation", 4, cells);
  for (vtkIdType c = 0; c < cells; ++c)
  {
    const opal::Domain& domain = layout.domains()[static_cast<std::size_t>(cellDomain[static_cast<std::size_t>(c)])];
    ids->SetValue(c, domain.Id);
    diameters->SetValue(c, static_cast<float>(domain.ParticleDiameter));
    normals->SetTuple(c, domain.Normal.data());
    lambdaMax->SetValue(c, static_cast<float>(opal::braggLambdaMax(domain.ParticleDiameter, refractiveIndex)));
    orientations->SetTuple(c, opal::latticeQuaternion(domain).data());
  }
  for (vtkDataArray* array : { static_cast<vtkDataArray*>(ids), static_cast<vtkDataArray*>(diameters),
         static_cast<vtkDataArray*>(normals), static_cast<vtkDataArray*>(lambdaMax),
         static_cast<vtkDataArray*>(orientations) })
  {
    output->GetCellData()->AddArray(array);
  }
  // Shown first coloured by the longest wavelength each domain diffracts
  // (ParaView colours by the active scalars), in the "Visible spectrum" map.
  output->GetCellData()->SetActiveScalars("BraggLambdaMax");
}

// The paper's layout: one polygon per domain.
vtkNew<vtkPolyData> makeDomainPolygons(const opal::DomainLayout& layout, double refractiveIndex)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polygons;
  std::vector<int> cellDomain;
  for (const opal::Domain& domain : layout.domains())
  {
    polygons->InsertNextCell(static_cast<vtkIdType>(domain.Vertices.size()));
    for (const auto& vertex : domain.Vertices)
    {
      polygons->InsertCellPoint(points->InsertNextPoint(vertex.data()));
    }
    cellDomain.push_back(domain.Id);
  }
  vtkNew<vtkPolyData> output;
  output->SetPoints(points);
  output->SetPolys(polygons);
  addDomainCellData(output, layout, cellDomain, refractiveIndex);
  return output;
}

// The Voronoi layout: the voxel faces bounding each ordered cell.
vtkNew<vtkPolyData> makeCellBoundaries(const opal::Grid& grid, const opal::DomainLayout& layout, double refractiveIndex)
{
  const opal::CellBoundaryMesh mesh = opal::orderedCellBoundaries(grid, layout);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.Points.size()));
  for (std::size_t p = 0; p < mesh.Points.size(); ++p)
  {
    points->SetPoint(static_cast<vtkIdType>(p), mesh.Points[p].data());
  }
  vtkNew<vtkCellArray> quads;
  quads->AllocateExact(static_cast<vtkIdType>(mesh.Faces.size()), 4 * static_cast<vtkIdType>(mesh.Faces.size()));
  for (const std::array<int, 4>& face : mesh.Faces)
  {
    const vtkIdType ids[4] = { face[0], face[1], face[2], face[3] };
    quads->InsertNextCell(4, ids);
  }
  vtkNew<vtkPolyData> output;
  output->SetPoints(points);
  output->SetPolys(quads);
  addDomainCellData(output, layout, mesh.FaceDomain, refractiveIndex);
  return output;
}
} // namespace

std::shared_ptr<const opal::DomainLayout> vtkOpalSource::BuildLayout(
  const opal::ModelParameters& parameters, bool refused)
{
  // Keyed on the settings, not the modification time: an abort's reset of
  // AbortExecute modifies one rank's source alone.
  const std::string settings = vtkOpalSharedVoronoiCells::SettingsOf(parameters);
  if (this->Layout && this->LayoutSettings == settings)
  {
    return refused ? nullptr : this->Layout;
  }
  this->LastVoronoiCellShares = 0;
  this->Layout = nullptr;
  this->Polygons = nullptr;
  const auto progress = [this](double fraction) {
    this->UpdateProgress(LayoutProgressShare * fraction);
    return !this->GetAbortExecute();
  };
  std::optional<opal::DomainLayout> built;
  const bool voronoi = parameters.DomainLayout == opal::DomainLayoutKind::Voronoi;
  // Every rank takes part once per change of the settings, whether it was
  // refused, aborted or holds nothing: so the ranks' entries depend on the
  // settings alone, alike on every rank (a rank that needs the layout again
  // later builds it alone).
  if (voronoi && vtkOpalRankAgreement::Ranks(this->Controller) > 1 && this->SharedSettings != settings)
  {
    this->SharedSettings = settings;
    const vtkOpalRankShares::Result shared = vtkOpalSharedVoronoiCells::Build(
      this->Controller, refused, parameters, progress, [this] { return this->GetAbortExecute() != 0; }, built);
    this->LastVoronoiCellShares = shared.Shares;
    if (shared.Aborted)
    {
      return nullptr; // a rank aborted its share: every rank's request aborts
    }
  }
  if (refused)
  {
    return nullptr;
  }
  if (!built)
  {
    built = opal::DomainLayout::build(parameters, progress);
    this->LastVoronoiCellShares = voronoi && !built->aborted() ? 1 : 0;
  }
  auto layout = std::make_shared<opal::DomainLayout>(std::move(*built));
  if (layout->aborted())
  {
    return nullptr;
  }
  if (const std::string small = opal::smallShapeWarning(parameters); !small.empty())
  {
    vtkWarningMacro(<< small);
  }
  if (layout->placedCount() < layout->requestedCount())
  {
    vtkWarningMacro("DomainCount: only " << layout->placedCount() << " of " << layout->requestedCount()
                                         << " domains could be placed within MaxPlacementAttempts ("
                                         << parameters.MaxPlacementAttempts
                                         << "); DomainsPlaced in the field data says how many.");
  }
  this->Layout = layout;
  this->LayoutSettings = settings;
  return layout;
}

vtkPolyData* vtkOpalSource::LayoutPolygons(const opal::ModelParameters& parameters)
{
  if (!this->Polygons)
  {
    const opal::Grid grid = opal::Grid::fromParameters(parameters);
    this->Polygons = this->Layout->hasCells() ? makeCellBoundaries(grid, *this->Layout, parameters.RefractiveIndex)
                                              : makeDomainPolygons(*this->Layout, parameters.RefractiveIndex);
  }
  return this->Polygons;
}

bool vtkOpalSource::FillVolume(
  vtkImageData* image, const opal::ModelParameters& parameters, const opal::DomainLayout& layout)
{
  const int* extent = image->GetExtent();
  const vtkIdType count = image->GetNumberOfPoints();
  // The description's arrays only with ALL_ARRAYS; the render's always.
  const bool describes = this->OutputArrays == ALL_ARRAYS;
  const vtkIdType described = describes ? count : 0;
  auto voxelType = makePointArray<vtkUnsignedCharArray>("VoxelType", 1, described);
  auto diameter = makePointArray<vtkFloatArray>("ParticleDiameter", 1, described);
  auto normal = makePointArray<vtkFloatArray>("Normal", 3, described);
  auto domainId = makePointArray<vtkIntArray>("DomainId", 1, count);
  auto lambdaMax = makePointArray<vtkFloatArray>("BraggLambdaMax", 1, described);
  auto lambdaMin = makePointArray<vtkFloatArray>("BraggLambdaMin", 1, described);
  auto scattering = makePointArray<vtkFloatArray>("ScatteringCoefficient", 1, count);
  auto distance = makePointArray<vtkFloatArray>("SurfaceDistance", 1, count);
  auto orientation = makePointArray<vtkFloatArray>("LatticeOrientation", 4, described);
  // Only with a Voronoi layout, only when the model absorbs (docs/design.md §2.9, §2.10).
  auto cellId = makePointArray<vtkIntArray>("CellId", 1, layout.hasCells() ? described : 0);
  const bool absorbs = parameters.absorbs();
  auto absorption = makePointArray<vtkFloatArray>("AbsorptionCoefficient", 1, absorbs ? count : 0);
  auto exponent = makePointArray<vtkFloatArray>("AbsorptionExponent", 1, absorbs ? count : 0);
  // The filler leaves out what it is given no array for.
  auto into = [](auto& array) { return array->GetNumberOfTuples() > 0 ? array->GetPointer(0) : nullptr; };
  const opal::VolumeFields fields{ into(voxelType), into(diameter), into(normal), into(domainId), into(lambdaMax),
    into(lambdaMin), into(scattering), into(distance), into(cellId), into(absorption), into(exponent),
    into(orientation) };

  if (count > 0 && !this->FillSlabs(extent, opal::VolumeFiller(parameters, layout), fields))
  {
    return false;
  }
  vtkPointData* pointData = image->GetPointData();
  if (describes)
  {
    pointData->SetScalars(voxelType);
    pointData->AddArray(diameter);
    pointData->SetNormals(normal);
  }
  // In the same order whatever the choice; an empty piece names the same arrays.
  const std::pair<vtkDataArray*, bool> arrays[] = { { domainId, true }, { lambdaMax, describes },
    { lambdaMin, describes }, { scattering, true }, { distance, true }, { orientation, describes },
    { cellId, describes && layout.hasCells() }, { absorption, absorbs }, { exponent, absorbs } };
  for (const auto& [array, present] : arrays)
  {
    if (present)
    {
      pointData->AddArray(array);
    }
  }
  if (!describes)
  {
    pointData->SetActiveScalars("ScatteringCoefficient");
  }
  return true;
}

bool vtkOpalSource::FillSlabs(const int* extent, const opal::VolumeFiller& filler, const opal::VolumeFields& fields)
{
  // Slab by slab in parallel, reporting progress and honouring abort between slabs.
  const std::array<int, 6> fillExtent{ extent[0], extent[1], extent[2], extent[3], extent[4], extent[5] };
  const int slabs = extent[5] - extent[4] + 1;
  const int chunk = std::max(1, slabs / 20);
  for (int k = extent[4]; k <= extent[5]; k += chunk)
  {
    if (this->GetAbortExecute())
    {
      return false;
    }
    const int kEnd = std::min(extent[5] + 1, k + chunk);
    opal::parallelFor(k, kEnd, [&](int begin, int end) { filler.fill(fillExtent, begin, end, fields); });
    this->UpdateProgress(
      LayoutProgressShare + (1 - LayoutProgressShare) * (kEnd - extent[4]) / static_cast<double>(slabs));
  }
  return true;
}

int vtkOpalSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  const opal::ModelParameters parameters = this->GetModelParameters();
  // Within the grid: a request left from a larger grid (a refused one) asks
  // beyond it, and its memory is not this grid's.
  vtkInformation* imageInfo = outputVector->GetInformationObject(0);
  int extent[6];
  imageInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), extent);
  for (int a = 0; a < 3; ++a)
  {
    extent[2 * a] = std::max(extent[2 * a], 0);
    extent[2 * a + 1] = std::min(extent[2 * a + 1], parameters.Dimensions[a] - 1);
  }
  // A refused rank still takes part in the ranks' shared layout.
  const bool refused = this->Refuses(extent);
  this->UpdateProgress(0.0);
  std::shared_ptr<const opal::DomainLayout> layout;
  try
  {
    layout = this->BuildLayout(parameters, refused);
  }
  catch (const std::exception& e) // out of memory, or the ranks' exchange failed
  {
    vtkErrorMacro("The domain layout could not be built: " << e.what());
  }
  if (!layout)
  {
    return 0;
  }
  const opal::Grid grid = opal::Grid::fromParameters(parameters);

  vtkImageData* image = vtkImageData::GetData(imageInfo);
  image->SetExtent(extent);
  image->SetSpacing(grid.Spacing.data());
  image->SetOrigin(grid.Origin.data());
  if (!this->FillVolume(image, parameters, *layout))
  {
    image->Initialize();
    return 0;
  }
  vtkOpalFieldData::AddModelParameters(image, parameters, this->Preset, layout->placedCount());
  vtkOpalFieldData::AddDomainTable(image, *layout);

  // The layout is small: the first piece carries all of it, the others none.
  vtkInformation* polyInfo = outputVector->GetInformationObject(1);
  vtkPolyData* polygons = vtkPolyData::GetData(polyInfo);
  const int piece = polyInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    ? polyInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER())
    : 0;
  if (piece == 0)
  {
    polygons->ShallowCopy(this->LayoutPolygons(parameters));
  }
  else
  {
    polygons->Initialize();
  }
  vtkOpalFieldData::AddModelParameters(polygons, parameters, this->Preset, layout->placedCount());
  this->UpdateProgress(1.0);
  return 1;
}

void vtkOpalSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  OPAL_MODEL_PARAMETERS(OPAL_VTK_PRINT)
  vtkOpalArrayCopy::print(os, indent, "Preset", this->Preset);
  vtkOpalArrayCopy::print(os, indent, "OutputArrays", this->OutputArrays);
}
