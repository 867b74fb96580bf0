#pragma once
// The MPM default: one velocity field on the grid, so bodies stick where they touch.
namespace cosmpm::contact {

struct SingleField {
  static constexpr const char* name() { return "single-field no-slip"; }
};

}  // namespace cosmpm::contact
