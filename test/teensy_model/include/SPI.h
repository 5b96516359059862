#pragma once
// SPI library (SPI.h, Teensy 3.x part): transactions and 16-bit transfers.
#include <cstdint>

#define SPI_MODE0 0x00
#define SPI_MODE1 0x04
#define SPI_MODE2 0x08
#define SPI_MODE3 0x0C
#define MSBFIRST 1
#define LSBFIRST 0

class SPISettings {
 public:
  SPISettings(uint32_t clock, uint8_t bit_order, uint8_t data_mode) : clock(clock), bit_order(bit_order), mode(data_mode) {}
  uint32_t clock;
  uint8_t bit_order;
  uint8_t mode;
};

class SPIClass {
 public:
  void begin();
  void beginTransaction(const SPISettings& settings);
  uint16_t transfer16(uint16_t data);
  void endTransaction();
};
extern SPIClass SPI;
