// HDF5 frames and their XDMF index: every field written is read back with the plain HDF5 C
// API and compared exactly (values are stored as doubles and int32, so the round trip has no
// rounding: tolerance 0); the XDMF file is checked to be well-formed XML whose every HDF
// reference names an existing dataset of the declared shape.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/io/hdf5.hpp"
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
}  // namespace

TEST_CASE("a particle frame round-trips every field exactly") {
  const auto dir = output_dir("frame_round_trip");
  const Store2 store = random_store(37);
  io::ParticleFrameWriter writer(dir, "block");
  const auto path = writer.write(store, 0.25, 10);
  CHECK(path == dir / "block_000000.h5");
  CHECK(writer.frame_count() == 1);
  CHECK(read_root_double(path, "time") == 0.25);
  CHECK(read_root_double(path, "step") == 10.0);
  CHECK(read_root_double(path, "particle_count") == 37.0);

  const Index n = store.size();
  auto check_vectors = [&](const std::string& name, auto&& value_of) {
    const RawDataset data = read_raw(path, "/" + name);
    REQUIRE_MESSAGE(data.ok, name);
    REQUIRE(data.dims == std::vector<hsize_t>{static_cast<hsize_t>(n), 2});
    const RawDataset padded = read_raw(path, "/" + name + "3");
    REQUIRE_MESSAGE(padded.ok, (name + "3"));
    REQUIRE(padded.dims == std::vector<hsize_t>{static_cast<hsize_t>(n), 3});
    for (Index p = 0; p < n; ++p) {
      const Vec<2> v = value_of(p);
      CHECK(data.values[2 * p] == v[0]);
      CHECK(data.values[2 * p + 1] == v[1]);
      CHECK(padded.values[3 * p] == v[0]);
      CHECK(padded.values[3 * p + 1] == v[1]);
      CHECK(padded.values[3 * p + 2] == 0.0);
    }
  };
  const auto& x = store.get<field::Position<2>>();
  const auto& x0 = store.get<field::InitialPosition<2>>();
  check_vectors("position", [&](Index p) { return x[p]; });
  check_vectors("velocity", [&](Index p) { return store.get<field::Velocity<2>>()[p]; });
  // Displacement from the start, formed the same way in double: exact.
  check_vectors("displacement", [&](Index p) { return Vec<2>(x[p] - x0[p]); });

  const RawDataset mass = read_raw(path, "/mass");
  const RawDataset body = read_raw(path, "/body");
  const RawDataset gradient = read_raw(path, "/velocity_gradient");
  const RawDataset stress = read_raw(path, "/stress");
  const RawDataset strain = read_raw(path, "/strain");
  const RawDataset plastic = read_raw(path, "/plastic");
  const RawDataset shear = read_raw(path, "/plastic_shear_strain");
  REQUIRE(mass.ok);
  REQUIRE(body.ok);
  REQUIRE(gradient.ok);
  REQUIRE(stress.ok);
  REQUIRE(strain.ok);
  REQUIRE(plastic.ok);
  REQUIRE(shear.ok);
  CHECK(gradient.dims == std::vector<hsize_t>{37, 4});
  CHECK(stress.dims == std::vector<hsize_t>{37, 4});
  CHECK(plastic.dims == std::vector<hsize_t>{37});
  CHECK_FALSE(read_raw(path, "/state").ok);  // the state is written per label only
  for (Index p = 0; p < n; ++p) {
    CHECK(mass.values[p] == store.get<field::Mass>()[p]);
    CHECK(body.values[p] == static_cast<double>(store.get<field::Body>()[p]));
    const Mat<2>& L = store.get<field::VelocityGradient<2>>()[p];
    // Row-major: L_xx, L_xy, L_yx, L_yy.
    CHECK(gradient.values[4 * p + 0] == L(0, 0));
    CHECK(gradient.values[4 * p + 1] == L(0, 1));
    CHECK(gradient.values[4 * p + 2] == L(1, 0));
    CHECK(gradient.values[4 * p + 3] == L(1, 1));
    for (int k = 0; k < 4; ++k) {
      CHECK(stress.values[4 * p + k] == store.get<field::Stress<PlasticModel>>()[p][k]);
      CHECK(strain.values[4 * p + k] == store.get<field::Strain<PlasticModel>>()[p][k]);
    }
    const auto& state = store.get<field::MaterialState<PlasticModel>>()[p];
    CHECK(plastic.values[p] == state.plastic);
    CHECK(shear.values[p] == state.plastic_shear_strain);
  }
}

TEST_CASE("the XDMF index is well-formed and references existing datasets of its shapes") {
  const auto dir = output_dir("xdmf");
  io::ParticleFrameWriter writer(dir, "series");
  // Particle counts change between frames (5, 8, 8): each frame declares its own.
  const std::array<Index, 3> counts{5, 8, 8};
  const std::array<double, 3> times{0.0, 0.1, 1.0 / 3.0};
  for (int f = 0; f < 3; ++f) {
    writer.write(random_store(counts[f], 7u + static_cast<unsigned>(f)), times[f], f * 100);
  }
  const std::string xml = read_text(writer.xdmf_path());
  bool well_formed = false;
  const auto elements = parse_xml(xml, well_formed);
  CHECK(well_formed);

  std::vector<double> listed_times;
  int references = 0;
  int frame = -1;
  std::vector<std::string> attribute_names;
  for (const auto& element : elements) {
    if (element.name == "Time") listed_times.push_back(std::stod(element.attributes.at("Value")));
    if (element.name == "Topology") {
      ++frame;
      CHECK(element.attributes.at("TopologyType") == "Polyvertex");
      CHECK(std::stol(element.attributes.at("NumberOfElements")) == counts[frame]);
    }
    if (element.name == "Attribute" && frame == 0) {
      attribute_names.push_back(element.attributes.at("Name"));
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
  // Per frame: the geometry; initial_position, velocity, displacement (vectors); mass, body,
  // plastic, plastic_shear_strain (scalars); 4 + 4 + 4 components of L, stress, strain:
  // 1 + 3 + 4 + 12 = 20.
  CHECK(references == 3 * 20);
  for (const char* name : {"velocity", "displacement", "stress_xx", "stress_xy", "strain_zz",
                           "plastic", "plastic_shear_strain", "velocity_gradient_yx", "body"}) {
    CHECK_MESSAGE(
        std::find(attribute_names.begin(), attribute_names.end(), name) != attribute_names.end(),
        name);
  }
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
  CHECK(read_raw(dir / "run_000000.h5", "/position").ok);
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
  CHECK(writer.resume<Store2>(0.1 * 2) == 3);
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
