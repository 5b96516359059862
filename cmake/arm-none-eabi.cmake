# Cross toolchain: Debian's gcc-arm-none-eabi for the Teensy 3.6's Cortex-M4F.
set(CMAKE_SYSTEM_NAME Generic)
set(CMAKE_SYSTEM_PROCESSOR arm)
set(CMAKE_C_COMPILER arm-none-eabi-gcc)
set(CMAKE_CXX_COMPILER arm-none-eabi-g++)
set(CMAKE_ASM_COMPILER arm-none-eabi-gcc)
set(CMAKE_TRY_COMPILE_TARGET_TYPE STATIC_LIBRARY)

# The flags the firmware is built with (PlatformIO's platform-teensy
# builder/frameworks/arduino.py for teensy36, default "faster" profile: -O2 is
# set by the cortex-m4 preset), so the measured code is the shipped code.
set(FF_M4_FLAGS "-mcpu=cortex-m4 -mthumb -mfpu=fpv4-sp-d16 -mfloat-abi=hard -ffunction-sections -fdata-sections \
-fsingle-precision-constant -mno-unaligned-access -DF_CPU=180000000 -D__MK66FX1M0__ -DTEENSYDUINO=159 -DARDUINO=10805")
set(CMAKE_C_FLAGS_INIT "${FF_M4_FLAGS}")
set(CMAKE_CXX_FLAGS_INIT "${FF_M4_FLAGS} -fno-exceptions -fno-rtti -felide-constructors -fno-threadsafe-statics")
set(CMAKE_EXE_LINKER_FLAGS_INIT "-Wl,--gc-sections")

set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
