// HDF5 frames (format version 2) and their XDMF index: every field written is read back with
// the plain HDF5 C API and compared exactly (values are copied as doubles and int32, so the
// round trip has no rounding: tolerance 0), in the shapes ParaView's readers read alike
// (N, N x 3, N x 9); every dataset says its unit; the XDMF file is well-formed XML whose
// every HDF reference names an existing dataset of the declared shape.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cosmpm/contact/rigid_contact.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape/linear.hpp"
#include "cosmpm/simulation.hpp"
#include "cosmpm/version.hpp"
#include "helpers.hpp"

namespace {
using namespace cosmpm;
using namespace cosmpm::test_io;
namespace field = particles::field;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  // text directly inside (DataItem contents)
};

// A small XML reader, enough for XDMF: returns every element in document order and sets
// `well_formed` to whether the tags nest properly (and are all closed).
std::vector<XmlElement> parse_xml(const std::string& xml, bool& well_formed) {
  std::vector<XmlElement> elements;
  std::vector<std::size_t> open;  // indices into elements
  well_formed = true;
  const std::regex attribute_pattern(R"re(([A-Za-z_]+)="([^"]*)")re");
  std::size_t pos = 0;
  while ((pos = xml.find('<', pos)) != std::string::npos) {
    const std::size_t end = xml.find('>', pos);
    if (end == std::string::npos) {
      well_formed = false;
      break;
    }
    const std::string tag = xml.substr(pos + 1, end - pos - 1);
    if (!open.empty() && elements[open.back()].text.empty()) {
      // Text between the previous tag and this one belongs to the innermost open element.
      const std::size_t previous_end = xml.rfind('>', pos - 1);
      elements[open.back()].text = xml.substr(previous_end + 1, pos - previous_end - 1);
    }
    pos = end + 1;
    if (tag.empty() || tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (open.empty() || elements[open.back()].name != name) well_formed = false;
      if (!open.empty()) open.pop_back();
      continue;
    }
    const bool self_closing = tag.back() == '/';
    XmlElement element;
    element.name = tag.substr(0, tag.find_first_of(" /"));
    for (std::sregex_iterator it(tag.begin(), tag.end(), attribute_pattern), last; it != last;
         ++it) {
      element.attributes[(*it)[1]] = (*it)[2];
    }
    elements.push_back(element);
    if (!self_closing) open.push_back(elements.size() - 1);
  }
  if (!open.empty()) well_formed = false;
  return elements;
}

std::vector<hsize_t> parse_dimensions(const std::string& text) {
  std::vector<hsize_t> dims;
  std::istringstream in(text);
  hsize_t n = 0;
  while (in >> n) dims.push_back(n);
  return dims;
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \n\t");
  const auto last = text.find_last_not_of(" \n\t");
  return first == std::string::npos ? "" : text.substr(first, last - first + 1);
}

// A state whose label collides with the Mass field: writing it must fail.
struct ClashingState {
  double value = 0.0;
  static constexpr std::array<std::string_view, 1> labels{"mass"};
  std::array<double, 1> values() const { return {value}; }
};
struct ClashingModel {
  using stress_type = SymTensor2D<double>;
  using strain_type = SymTensor2D<double>;
  using state_type = ClashingState;
};
using ClashingStore =
    particles::Store<field::Position<2>, field::Mass, field::MaterialState<ClashingModel>>;
// A field of a user's own, with its unit on the tag, and an Eigen shape ParaView has no type
// for (5 components: written as 5 scalars).
struct Temperature {
  using value_type = double;
  static constexpr const char* label() { return "temperature"; }
  static constexpr const char* units() { return "K"; }
  static constexpr const char* description() { return "grain temperature"; }
};
struct Fabric {
  using value_type = Eigen::Matrix<double, 5, 1>;
  static constexpr const char* label() { return "fabric"; }
};
using CosseratModel = material::CosseratElastic<>;
using RichStore = particles::Store<field::Position<2>, field::HalfWidth<2>,
                                   field::DeformationGradient<2>, field::Stress<CosseratModel>,
                                   field::Strain<CosseratModel>, Temperature, Fabric>;

RichStore rich_store(Index count) {
  RichStore store;
  store.append(count);
  for (Index p = 0; p < count; ++p) {
    const double s = static_cast<double>(p + 1);
    store.get<field::Position<2>>()[p] = Vec<2>(s, -s);
    store.get<field::HalfWidth<2>>()[p] = Vec<2>(0.25, 0.125);
    Mat<2> F;
    F << 1.0 + s, 0.5 * s, -0.25 * s, 2.0;
    store.get<field::DeformationGradient<2>>()[p] = F;
    for (int k = 0; k < 7; ++k) {
      store.get<field::Stress<CosseratModel>>()[p][k] = 100.0 * s + k;
      store.get<field::Strain<CosseratModel>>()[p][k] = -1e-3 * s - 1e-4 * k;
    }
    store.get<Temperature>()[p] = 290.0 + s;
    for (int k = 0; k < 5; ++k) store.get<Fabric>()[p][k] = 10.0 * s + k;
  }
  return store;
}

// Row-major 3 x 3 index.
constexpr int t9(int i, int j) {
  return 3 * i + j;
}

}  // namespace

TEST_CASE("a particle frame round-trips every field exactly, in ParaView's shapes") {
  const auto dir = output_dir("frame_round_trip");
  const Store2 store = random_store(37);
  io::ParticleFrameWriter writer(dir, "block");
  const auto path = writer.write(store, 0.25, 10);
  CHECK(path == dir / "block_000000.h5");
  CHECK(writer.frame_count() == 1);
  CHECK(read_root_double(path, "time") == 0.25);
  CHECK(read_root_double(path, "step") == 10.0);
  CHECK(read_root_double(path, "particle_count") == 37.0);
  CHECK(read_root_double(path, "version") == 2.0);
  CHECK(read_root_double(path, "dimension") == 2.0);
  CHECK(read_string_attribute(path, "/", "format") == "cosmpm-frame");
  CHECK(read_string_attribute(path, "/", "library") == "cosmpm " + std::to_string(version_major) +
                                                           "." + std::to_string(version_minor) +
                                                           "." + std::to_string(version_patch));
  CHECK(read_string_attribute(path, "/", "sign_convention").find("tension positive") !=
        std::string::npos);

  const Index n = store.size();
  const auto N = static_cast<hsize_t>(n);
  // Vectors are N x 3, the third component zero in 2D.
  auto check_vectors = [&](const std::string& name, auto&& value_of) {
    const RawDataset data = read_raw(path, "/particles/" + name);
    REQUIRE_MESSAGE(data.ok, name);
    REQUIRE(data.dims == std::vector<hsize_t>{N, 3});
    for (Index p = 0; p < n; ++p) {
      const Vec<2> v = value_of(p);
      CHECK(data.values[3 * p] == v[0]);
      CHECK(data.values[3 * p + 1] == v[1]);
      CHECK(data.values[3 * p + 2] == 0.0);
    }
    CHECK(read_string_attribute(path, "/particles/" + name, "components") == "x y z");
  };
  const auto& x = store.get<field::Position<2>>();
  const auto& x0 = store.get<field::InitialPosition<2>>();
  check_vectors("position", [&](Index p) { return x[p]; });
  check_vectors("initial_position", [&](Index p) { return x0[p]; });
  check_vectors("velocity", [&](Index p) { return store.get<field::Velocity<2>>()[p]; });
  // Displacement from the start, formed the same way in double: exact.
  check_vectors("displacement", [&](Index p) { return Vec<2>(x[p] - x0[p]); });

  const RawDataset ids = read_raw(path, "/particles/connectivity");
  REQUIRE(ids.ok);
  CHECK(ids.dims == std::vector<hsize_t>{N, 1});
  for (Index p = 0; p < n; ++p) CHECK(ids.values[p] == static_cast<double>(p));

  const RawDataset mass = read_raw(path, "/particles/mass");
  const RawDataset body = read_raw(path, "/particles/body");
  const RawDataset gradient = read_raw(path, "/particles/velocity_gradient");
  const RawDataset stress = read_raw(path, "/particles/stress");
  const RawDataset strain = read_raw(path, "/particles/strain");
  const RawDataset plastic = read_raw(path, "/particles/plastic");
  const RawDataset shear = read_raw(path, "/particles/plastic_shear_strain");
  const RawDataset separation = read_raw(path, "/particles/separation");
  for (const auto* data :
       {&mass, &body, &gradient, &stress, &strain, &plastic, &shear, &separation}) {
    REQUIRE(data->ok);
  }
  CHECK(gradient.dims == std::vector<hsize_t>{N, 9});
  CHECK(stress.dims == std::vector<hsize_t>{N, 9});
  CHECK(plastic.dims == std::vector<hsize_t>{N});
  CHECK_FALSE(read_raw(path, "/particles/state").ok);  // the state is written per label only
  for (Index p = 0; p < n; ++p) {
    CHECK(mass.values[p] == store.get<field::Mass>()[p]);
    CHECK(body.values[p] == static_cast<double>(store.get<field::Body>()[p]));
    const Mat<2>& L = store.get<field::VelocityGradient<2>>()[p];
    const double* l = gradient.values.data() + 9 * p;
    CHECK(l[t9(0, 0)] == L(0, 0));
    CHECK(l[t9(0, 1)] == L(0, 1));
    CHECK(l[t9(1, 0)] == L(1, 0));
    CHECK(l[t9(1, 1)] == L(1, 1));
    CHECK(l[t9(2, 2)] == 0.0);
    // [xx, yy, zz, xy] -> the symmetric 3 x 3 tensor.
    for (const auto* data : {&stress, &strain}) {
      const auto& stored = data == &stress ? store.get<field::Stress<PlasticModel>>()[p]
                                           : store.get<field::Strain<PlasticModel>>()[p];
      const double* t = data->values.data() + 9 * p;
      CHECK(t[t9(0, 0)] == stored[0]);
      CHECK(t[t9(1, 1)] == stored[1]);
      CHECK(t[t9(2, 2)] == stored[2]);
      CHECK(t[t9(0, 1)] == stored[3]);
      CHECK(t[t9(1, 0)] == stored[3]);
      CHECK(t[t9(0, 2)] == 0.0);
      CHECK(t[t9(2, 1)] == 0.0);
    }
    const auto& state = store.get<field::MaterialState<PlasticModel>>()[p];
    CHECK(plastic.values[p] == state.plastic);
    CHECK(shear.values[p] == state.plastic_shear_strain);
    CHECK(separation.values[p] == state.separation);
  }
  // Every dataset says its unit; tensors and vectors their components.
  CHECK(read_string_attribute(path, "/particles/stress", "units") == "Pa");
  CHECK(read_string_attribute(path, "/particles/stress", "components") ==
        "xx xy xz yx yy yz zx zy zz");
  CHECK(read_string_attribute(path, "/particles/strain", "units") == "1");
  CHECK(read_string_attribute(path, "/particles/velocity_gradient", "units") == "1/s");
  CHECK(read_string_attribute(path, "/particles/mass", "units") == "kg/m");  // per metre, 2D
  CHECK(read_string_attribute(path, "/particles/velocity", "units") == "m/s");
  CHECK(read_string_attribute(path, "/particles/position", "units") == "m");
  CHECK(read_string_attribute(path, "/particles/plastic", "units") == "1");
  CHECK(read_string_attribute(path, "/particles/body", "units") == "1");
}

TEST_CASE("Cosserat tensors, F, half-width and fields of one's own in a frame") {
  const auto dir = output_dir("frame_layouts");
  const RichStore store = rich_store(3);
  io::ParticleFrameWriter writer(dir, "rich");
  const auto path = writer.write(store, 0.0, 0);
  const RawDataset stress = read_raw(path, "/particles/stress");
  const RawDataset couple = read_raw(path, "/particles/couple_stress");
  const RawDataset strain = read_raw(path, "/particles/strain");
  const RawDataset curvature = read_raw(path, "/particles/curvature");
  const RawDataset F = read_raw(path, "/particles/deformation_gradient");
  const RawDataset half = read_raw(path, "/particles/half_width_in_cells");
  const RawDataset temperature = read_raw(path, "/particles/temperature");
  REQUIRE(stress.ok);
  REQUIRE(couple.ok);
  REQUIRE(strain.ok);
  REQUIRE(curvature.ok);
  REQUIRE(F.ok);
  REQUIRE(half.ok);
  REQUIRE(temperature.ok);
  for (Index p = 0; p < 3; ++p) {
    // [xx, yy, zz, xy, yx, m_31, m_32]: sigma_xy and sigma_yx stay apart.
    const auto& s = store.get<field::Stress<CosseratModel>>()[p];
    const double* t = stress.values.data() + 9 * p;
    CHECK(t[t9(0, 0)] == s[0]);
    CHECK(t[t9(1, 1)] == s[1]);
    CHECK(t[t9(2, 2)] == s[2]);
    CHECK(t[t9(0, 1)] == s[3]);
    CHECK(t[t9(1, 0)] == s[4]);
    CHECK(couple.values[3 * p] == s[5]);
    CHECK(couple.values[3 * p + 1] == s[6]);
    CHECK(couple.values[3 * p + 2] == 0.0);
    const auto& e = store.get<field::Strain<CosseratModel>>()[p];
    CHECK(strain.values[9 * p + t9(1, 0)] == e[4]);
    CHECK(curvature.values[3 * p + 1] == e[6]);
    // Plane strain: F_zz = 1.
    const Mat<2>& f = store.get<field::DeformationGradient<2>>()[p];
    CHECK(F.values[9 * p + t9(0, 1)] == f(0, 1));
    CHECK(F.values[9 * p + t9(1, 0)] == f(1, 0));
    CHECK(F.values[9 * p + t9(2, 2)] == 1.0);
    CHECK(half.values[3 * p] == 0.25);
    CHECK(half.values[3 * p + 1] == 0.125);
    CHECK(temperature.values[p] == 291.0 + static_cast<double>(p));
    for (int k = 0; k < 5; ++k) {
      const RawDataset component = read_raw(path, "/particles/fabric_" + std::to_string(k));
      REQUIRE(component.ok);
      CHECK(component.values[p] == store.get<Fabric>()[p][k]);
    }
  }
  CHECK(read_string_attribute(path, "/particles/couple_stress", "units") == "N/m");
  CHECK(read_string_attribute(path, "/particles/curvature", "units") == "1/m");
  CHECK(read_string_attribute(path, "/particles/half_width_in_cells", "units") == "cell widths");
  CHECK(read_string_attribute(path, "/particles/temperature", "units") == "K");
  CHECK(read_string_attribute(path, "/particles/temperature", "description") ==
        "grain temperature");
  CHECK(read_string_attribute(path, "/particles/fabric_0", "units") == "unknown");
}

TEST_CASE("the XDMF index is well-formed and references existing datasets of its shapes") {
  const auto dir = output_dir("xdmf");
  io::ParticleFrameWriter writer(dir, "series");
  // Particle counts change between frames (5, 8, 8): each frame declares its own.
  const std::array<Index, 3> counts{5, 8, 8};
  const std::array<double, 3> times{0.0, 0.1, 1.0 / 3.0};
  for (int f = 0; f < 3; ++f) {
    writer.write(random_store(counts[f], 7u + static_cast<unsigned>(f)), times[f], f * 100,
                 {{"travel", 0.001 * f, "m", "blade travel"}});
  }
  const std::string xml = read_text(writer.xdmf_path());
  bool well_formed = false;
  const auto elements = parse_xml(xml, well_formed);
  CHECK(well_formed);
  // No view into another array: Xdmf3 drops hyperslabs.
  CHECK(xml.find("HyperSlab") == std::string::npos);

  std::vector<double> listed_times;
  int references = 0;
  int frame = -1;
  std::map<std::string, std::string> types;  // attribute name -> AttributeType, frame 0
  std::vector<std::string> centres;
  for (const auto& element : elements) {
    if (element.name == "Time") listed_times.push_back(std::stod(element.attributes.at("Value")));
    if (element.name == "Topology") {
      ++frame;
      CHECK(element.attributes.at("TopologyType") == "Polyvertex");
      CHECK(std::stol(element.attributes.at("NumberOfElements")) == counts[frame]);
    }
    if (element.name == "Attribute") {
      centres.push_back(element.attributes.at("Center"));
      if (frame == 0) types[element.attributes.at("Name")] = element.attributes.at("AttributeType");
    }
    if (element.name != "DataItem" || element.attributes.count("Format") == 0 ||
        element.attributes.at("Format") != "HDF") {
      continue;
    }
    ++references;
    const std::string reference = trim(element.text);
    const auto colon = reference.find(':');
    REQUIRE(colon != std::string::npos);
    const auto file = dir / reference.substr(0, colon);
    const RawDataset data = read_raw(file, reference.substr(colon + 1));
    CHECK_MESSAGE(data.ok, reference);
    CHECK_MESSAGE(data.dims == parse_dimensions(element.attributes.at("Dimensions")), reference);
  }
  // Times are written exactly (shortest round-trip text), so they read back equal.
  REQUIRE(listed_times.size() == 3);
  for (int f = 0; f < 3; ++f) CHECK(listed_times[f] == times[f]);
  // Per frame: connectivity and geometry; initial_position, velocity, displacement
  // (vectors); mass, body, plastic, plastic_shear_strain, separation (scalars);
  // velocity_gradient, stress, strain (tensors); travel: 2 + 3 + 5 + 3 + 1 = 14.
  CHECK(references == 3 * 14);
  CHECK(types.at("velocity") == "Vector");
  CHECK(types.at("displacement") == "Vector");
  CHECK(types.at("stress") == "Tensor");
  CHECK(types.at("strain") == "Tensor");
  CHECK(types.at("velocity_gradient") == "Tensor");
  CHECK(types.at("mass") == "Scalar");
  CHECK(types.at("body") == "Scalar");
  CHECK(types.at("plastic") == "Scalar");
  CHECK(types.at("travel") == "Scalar");
  // The frame value is field data (one value per frame), everything else per point.
  CHECK(std::count(centres.begin(), centres.end(), "Grid") == 3);
  CHECK(std::count(centres.begin(), centres.end(), "Node") == 3 * 11);
  const RawDataset travel = read_raw(dir / "series_000002.h5", "/values/travel");
  REQUIRE(travel.ok);
  CHECK(travel.values == std::vector<double>{0.002});
  CHECK(read_string_attribute(dir / "series_000002.h5", "/values/travel", "units") == "m");
  // Each frame keeps its own entry of the index.
  CHECK(xml.find(read_string_attribute(dir / "series_000001.h5", "/", "xdmf")) !=
        std::string::npos);
}

namespace {
using BladeSim = Simulation<2, shape::Linear, continuum::Classical<material::LinearElastic<>>,
                            contact::RigidContact<2>>;
}

TEST_CASE("a frame of a simulation holds half-widths in metres, its rigid bodies and values") {
  const auto dir = output_dir("frame_of_sim");
  // Cells of 0.1 m x 0.05 m; 2 particles per cell and axis: half-width 0.25 cells.
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 0.5), {10, 10});
  contact::RigidContact<2> law;
  law.add_body(contact::RigidBody<2>::box(Vec<2>(0.1, 0.0), Vec<2>(0.15, 0.4))
                   .set_velocity(Vec<2>(0.01, 0.0)),
               contact::Interface::coulomb_angle(14.0));
  BladeSim sim(grid, material::LinearElastic<>(1e6, 0.3), {}, law);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.15, 0.0), Vec<2>(1.0, 0.2), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  sim.step(1e-4);
  io::ParticleFrameWriter writer(dir, "run",
                                 {.run_parameters = "depth = 0.2\n", .body_names = {"blade"}});
  const auto path = writer.write(sim, {{"blade_travel", 1e-6, "m", "blade travel"}});
  const RawDataset half = read_raw(path, "/particles/half_width");
  REQUIRE(half.ok);
  CHECK(half.values[0] == 0.25 * 0.1);
  CHECK(half.values[1] == 0.25 * 0.05);
  CHECK(read_string_attribute(path, "/particles/half_width", "units") == "m");
  CHECK(read_string_attribute(path, "/", "run_parameters") == "depth = 0.2\n");
  const RawDataset vertices = read_raw(path, "/bodies/blade/vertices");
  REQUIRE(vertices.ok);
  CHECK(vertices.dims == std::vector<hsize_t>{4, 3});
  const auto& corners = sim.contact().body(0).vertices();
  for (std::size_t v = 0; v < 4; ++v) {
    CHECK(vertices.values[3 * v] == corners[v][0]);
    CHECK(vertices.values[3 * v + 1] == corners[v][1]);
  }
  const RawDataset force = read_raw(path, "/bodies/blade/force_on_material");
  REQUIRE(force.ok);
  CHECK(force.values[0] == sim.contact().force_on_material(0)[0]);
  CHECK(read_string_attribute(path, "/bodies/blade/force_on_material", "units") == "N/m");
  const RawDataset velocity = read_raw(path, "/bodies/blade/velocity");
  REQUIRE(velocity.ok);
  CHECK(velocity.values == std::vector<double>{0.01, 0.0, 0.0});
  // The bodies have their own index; the particles' index holds only particles (ParaView's
  // Xdmf3ReaderS would merge both into one dataset that cannot be coloured by stress).
  const std::string bodies = read_text(writer.bodies_xdmf_path());
  CHECK(bodies.find("TopologyType=\"Polygon\"") != std::string::npos);
  CHECK(bodies.find("Name=\"blade\"") != std::string::npos);
  CHECK(bodies.find("Center=\"Cell\"") != std::string::npos);
  const std::string particles = read_text(writer.xdmf_path());
  CHECK(particles.find("Polygon") == std::string::npos);
  CHECK(particles.find("Center=\"Grid\"") != std::string::npos);
}

TEST_CASE("a failing frame leaves no file behind and the frames before stay readable") {
  const auto dir = output_dir("failing_frame");
  {
    io::ParticleFrameWriter writer(dir, "run");
    writer.write(random_store(4), 0.5, 1);
    ClashingStore bad;
    bad.append(3);
    // The state label "mass" would overwrite the mass dataset: refused mid-frame.
    CHECK_THROWS_AS(writer.write(bad, 1.0, 2), Error);
    CHECK(writer.frame_count() == 1);
  }
  // Only the complete frame and the index exist: no temporary, no half frame.
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    files.push_back(entry.path().filename().string());
  }
  std::sort(files.begin(), files.end());
  CHECK(files == std::vector<std::string>{"run.xdmf", "run_000000.h5"});
  CHECK(read_raw(dir / "run_000000.h5", "/particles/position").ok);
  CHECK(read_root_double(dir / "run_000000.h5", "time") == 0.5);
  const std::string xml = read_text(dir / "run.xdmf");
  CHECK(xml.find("run_000000.h5") != std::string::npos);
  CHECK(xml.find("run_000001.h5") == std::string::npos);
}

TEST_CASE("frame writer errors name the file or directory") {
  const auto dir = output_dir("frame_errors");
  // A directory that cannot be created (a file is in the way).
  std::ofstream(dir / "blocker") << "x";
  try {
    io::ParticleFrameWriter writer(dir / "blocker" / "sub", "run");
    FAIL("no error");
  } catch (const Error& error) {
    CHECK(std::string(error.what()).find("blocker") != std::string::npos);
  }
  CHECK_THROWS_AS(io::ParticleFrameWriter(dir, "a/b"), Error);
  // Reading a file that is not HDF5 names it.
  try {
    (void)io::Hdf5File::open_read(dir / "blocker");
    FAIL("no error");
  } catch (const Error& error) {
    CHECK(std::string(error.what()).find("blocker") != std::string::npos);
  }
}

TEST_CASE("resume re-lists the frames up to the restart time and continues numbering") {
  const auto dir = output_dir("resume");
  {
    io::ParticleFrameWriter writer(dir, "run");
    for (int f = 0; f < 4; ++f) writer.write(random_store(3), 0.1 * f, f);
  }
  io::ParticleFrameWriter writer(dir, "run");
  // Restart at t = 0.2: frames at 0, 0.1, 0.2 are kept (0.1 * 2 == 0.2 in double).
  CHECK(writer.resume(0.1 * 2) == 3);
  CHECK(writer.write(random_store(3), 0.25, 5) == dir / "run_000003.h5");
  const std::string xml = read_text(writer.xdmf_path());
  bool well_formed = false;
  const auto elements = parse_xml(xml, well_formed);
  CHECK(well_formed);
  std::vector<double> times;
  for (const auto& e : elements) {
    if (e.name == "Time") times.push_back(std::stod(e.attributes.at("Value")));
  }
  CHECK(times == std::vector<double>{0.0, 0.1, 0.1 * 2, 0.25});
}

TEST_CASE("resuming over frames of format version 1 fails naming the version") {
  const auto dir = output_dir("resume_v1");
  {
    // The root attributes of a version 1 frame (fields at the root, no index entry).
    io::Hdf5File old = io::Hdf5File::create(dir / "run_000000.h5");
    old.set_attribute("format", std::string("cosmpm-frame"));
    old.set_attribute("version", std::int64_t{1});
    old.set_attribute("time", 0.0);
    old.close();
  }
  io::ParticleFrameWriter writer(dir, "run");
  std::string message;
  try {
    writer.resume(1.0);
  } catch (const Error& error) {
    message = error.what();
  }
  CHECK(message.find("run_000000.h5") != std::string::npos);
  CHECK(message.find("frame format version 1") != std::string::npos);
  CHECK(message.find("version 2") != std::string::npos);
}

TEST_CASE("a full disk gives an Error with the system's reason and leaves no temporary file") {
  // /dev/full accepts opening and fails every write with ENOSPC: linking the temporary name
  // to it makes the next write meet a full disk, deterministically.
  if (!std::filesystem::exists("/dev/full")) return;
  const auto dir = output_dir("disk_full");
  io::ParticleFrameWriter writer(dir, "run");
  writer.write(random_store(3), 0.0, 0);
  auto fill = [](const std::filesystem::path& final_path) {
    std::filesystem::create_symlink("/dev/full", io::temporary_path(final_path));
  };
  std::string frame_error;
  fill(writer.frame_path(1));
  try {
    writer.write(random_store(300), 1.0, 1);
  } catch (const Error& error) {
    frame_error = error.what();
  }
  CHECK(frame_error.find("run_000001.h5") != std::string::npos);
  MESSAGE(frame_error);
  CHECK(frame_error.find("No space left on device") != std::string::npos);
  CHECK(writer.frame_count() == 1);
  std::string index_error;
  fill(writer.xdmf_path());
  try {
    writer.write(random_store(3), 2.0, 2);  // the frame is written, its index is not
  } catch (const Error& error) {
    index_error = error.what();
  }
  CHECK(index_error.find("run.xdmf") != std::string::npos);
  CHECK(index_error.find("No space left on device") != std::string::npos);
  // No temporary name is left behind, and the index still lists the complete frame 0.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    CHECK_MESSAGE(entry.path().string().find(".tmp") == std::string::npos, entry.path());
  }
  CHECK(read_text(writer.xdmf_path()).find("run_000000.h5") != std::string::npos);
  // The writer goes on once there is room again (resume lists both frames on disk).
  CHECK(writer.resume(10.0) == 2);
  CHECK(read_text(writer.xdmf_path()).find("run_000001.h5") != std::string::npos);
}
