#pragma once
// Test-only model of the Teensyduino calls firmware/src/main.cpp makes
// (Teensy 3.6, USB type USB_HID, F_CPU 180 MHz) — only those, each behaving
// as the core's source says (file names in teensy_model.hpp). Not
// Teensyduino: written here from reading it, so the binding compiles
// unchanged natively and runs in simulated time.
#include <cstddef>
#include <cstdint>

#include "IPAddress.h"

// ---- core_pins.h ---------------------------------------------------------------
#define HIGH 1
#define LOW 0
#define INPUT 0
#define OUTPUT 1
#define RISING 3
#define FALLING 2
#define CHANGE 4
#define A0 14
#define A1 15
#define A2 16
#define A3 17
#define A21 66
uint32_t micros();
uint32_t millis();
void delay(uint32_t ms);
void yield();
void pinMode(uint8_t pin, uint8_t mode);
void digitalWriteFast(uint8_t pin, uint8_t value);
uint8_t digitalReadFast(uint8_t pin);
#define digitalPinToInterrupt(p) ((p) < 58 ? (p) : -1)
void attachInterrupt(uint8_t pin, void (*function)(), int mode);
int analogRead(uint8_t pin);
void analogReadResolution(unsigned int bits);
void analogWriteResolution(uint32_t bits);
void analogWrite(uint8_t pin, int value);
void analogReference(uint8_t type);
void _reboot_Teensyduino_();
extern uint8_t yield_active_check_flags;
#define YIELD_CHECK_USB_SERIAL 0x1

// ---- kinetis.h: the registers the binding touches, as model memory -------------
namespace teensy_model_regs {
extern volatile uint32_t sim_scgc2;
extern volatile uint8_t dac0[4];  // DAT0L, DAT0H, C0 at [2] (the model reads them back)
extern volatile uint32_t demcr, dwt_ctrl;
extern volatile uint16_t wdog_refresh, wdog_unlock, wdog_tovalh, wdog_tovall, wdog_presc, wdog_stctrlh;
uint32_t dwt_cyccnt();
}  // namespace teensy_model_regs
#define SIM_SCGC2 (teensy_model_regs::sim_scgc2)
#define SIM_SCGC2_DAC0 ((uint32_t)0x00001000)
#define DAC0_DAT0L (teensy_model_regs::dac0[0])
#define DAC0_C0 (teensy_model_regs::dac0[2])
#define DAC_C0_DACEN ((uint8_t)0x80)
#define DAC_C0_DACRFS ((uint8_t)0x40)
#define ARM_DEMCR (teensy_model_regs::demcr)
#define ARM_DEMCR_TRCENA (1 << 24)
#define ARM_DWT_CTRL (teensy_model_regs::dwt_ctrl)
#define ARM_DWT_CTRL_CYCCNTENA (1 << 0)
#define ARM_DWT_CYCCNT (teensy_model_regs::dwt_cyccnt())
#define WDOG_REFRESH (teensy_model_regs::wdog_refresh)
#define WDOG_UNLOCK (teensy_model_regs::wdog_unlock)
#define WDOG_UNLOCK_SEQ1 ((uint16_t)0xC520)
#define WDOG_UNLOCK_SEQ2 ((uint16_t)0xD928)
#define WDOG_TOVALH (teensy_model_regs::wdog_tovalh)
#define WDOG_TOVALL (teensy_model_regs::wdog_tovall)
#define WDOG_PRESC (teensy_model_regs::wdog_presc)
#define WDOG_STCTRLH (teensy_model_regs::wdog_stctrlh)
#define WDOG_STCTRLH_ALLOWUPDATE ((uint16_t)0x0010)
#define WDOG_STCTRLH_WDOGEN ((uint16_t)0x0001)
void __disable_irq();
void __enable_irq();

// ---- usb_seremu.h (it declares this one; usb_dev.h has the rest) ------------------
extern volatile uint8_t usb_configuration;

// ---- usb_seremu.h / usb_mouse.h ----------------------------------------------------
class usb_seremu_class {
 public:
  int available();
  int read();
  size_t readBytes(char* buffer, size_t length);
  size_t write(const uint8_t* buffer, size_t size);
  int availableForWrite();
};
extern usb_seremu_class Serial;

class usb_mouse_class {
 public:
  void screenSize(uint16_t width, uint16_t height, bool mac = false);
  void moveTo(uint16_t x, uint16_t y);
};
extern usb_mouse_class Mouse;

// Defined by the sketch or, weakly, by the model (pins_teensy.c startup_default_middle_hook).
extern "C" void startup_middle_hook(void);
void setup();
void loop();
