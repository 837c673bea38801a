#pragma once
// evdev: Linux input devices with six axes (X Y Z RX RY RZ, each EV_ABS or
// EV_REL) and their buttons, read from /dev/input/eventN: how every 3D
// mouse is also seen on Linux, and the route that needs no hidraw
// permission (spacenavd's own). Ids "evdev:/dev/input/eventN".
//
// Implements: listing through sysfs (/sys/class/input/eventN/device/
// capabilities, so other nodes are not even opened; a node this user may
// not open is listed as not accessible), the USB location and serial (uniq)
// that let the registry skip a device already open through hidraw or
// spacenavd, hot-plug (changed() when the nodes in /dev/input change),
// unplug (kRemoved), SYN_DROPPED with a resync, relative devices whose
// release the kernel never reports (see evdev_input/evdev_input_device.h).
// Raw input is recorded as portable input_event records
// (parsers/evdev_event_parser.h), the layout as the report descriptor.
// Lacks: EVIOCGRAB (the desktop may also see the device, as without
// spacenavd), udev properties (libudev is not a dependency; sysfs has what
// is needed), the 3Dconnexion button maps of the quirks table (buttons are
// numbered in key-code order), telling a non-USB device without a serial
// from its hidraw twin (both have other physical keys).
//
// Registry priority: after spnav and hidapi, before libusb (which detaches
// the kernel driver and so removes the event node too).
//
// Thread safety: as every Backend and Device (types/device.h).

#include <memory>

#include "sculpt/hal/types/device.h"

namespace sculpt::hal {

std::unique_ptr<Backend> make_evdev_backend();

}  // namespace sculpt::hal
