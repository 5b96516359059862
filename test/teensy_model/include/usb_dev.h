#pragma once
// teensy3/usb_dev.h + usb_mem.h + usb_desc.h (USB_HID): the packet API. Arduino.h
// does not expose it (usb_undef.h hides usb_desc.h's endpoint numbers), so the
// binding includes this header itself, as on the Teensy.
#include <cstdint>

#define SEREMU_TX_ENDPOINT 1
#define SEREMU_RX_ENDPOINT 2
#define MOUSE_ENDPOINT 5
#define NUM_USB_BUFFERS 24

struct usb_packet_t {
  uint16_t len;
  uint16_t index;
  usb_packet_t* next;
  uint8_t buf[64];
};

extern "C" {
usb_packet_t* usb_rx(uint32_t endpoint);
void usb_free(usb_packet_t* p);
uint32_t usb_tx_packet_count(uint32_t endpoint);
}
