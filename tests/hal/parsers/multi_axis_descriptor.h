#pragma once
// A report descriptor of a non-3Dconnexion 6-DOF controller: usage page 1
// usage 8, report 1 with X Y Z Rx Ry Rz as 16-bit fields in [-500, 500],
// report 3 with four buttons and 4 bits of padding.

#include <cstdint>
#include <vector>

namespace sculpt::hal::test {

inline std::vector<uint8_t> multi_axis_descriptor(bool relative) {
  const uint8_t axis_flags = relative ? 0x06 : 0x02;  // data, variable, relative/absolute
  return {
      0x05, 0x01,              // usage page: generic desktop
      0x09, 0x08,              // usage: multi-axis controller
      0xA1, 0x01,              // collection: application
      0xA1, 0x00,              //   collection: physical
      0x85, 0x01,              //     report id 1
      0x16, 0x0C,       0xFE,  //     logical minimum -500
      0x26, 0xF4,       0x01,  //     logical maximum 500
      0x09, 0x30,       0x09, 0x31, 0x09, 0x32,
      0x09, 0x33,       0x09, 0x34, 0x09, 0x35,  // X Y Z Rx Ry Rz
      0x75, 0x10,                                //     report size 16
      0x95, 0x06,                                //     report count 6
      0x81, axis_flags,                          //     input
      0xC0,                                      //   end collection
      0x85, 0x03,                                //   report id 3
      0x05, 0x09,                                //   usage page: button
      0x19, 0x01,       0x29, 0x04,              // usage minimum 1, maximum 4
      0x15, 0x00,       0x25, 0x01,              // logical 0..1
      0x75, 0x01,       0x95, 0x04,              // 4 x 1 bit
      0x81, 0x02,                                //   input (data, variable, absolute)
      0x95, 0x01,       0x75, 0x04,              // padding 4 bits
      0x81, 0x01,                                //   input (constant)
      0xC0,                                      // end collection
  };
}

}  // namespace sculpt::hal::test
