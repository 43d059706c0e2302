#pragma once
// The C interface of the image module (native/images/oiio_codec.cpp, loaded by format/image_library).
// Functions return 0 or null on failure and then write a message into `error`: exactly
// FENESTRA_IMAGE_OUT_OF_MEMORY when an allocation failed (no exception crosses this interface).
#include <cstddef>

#define FENESTRA_IMAGE_ABI_VERSION 2
#define FENESTRA_IMAGE_OUT_OF_MEMORY "out of memory"

extern "C" {
typedef void (*fenestra_image_bytes_sink)(void* context, const char* bytes, size_t size);

int fenestra_image_abi_version();
// Opens an image and reads its size; the handle is closed by fenestra_image_close.
void* fenestra_image_open(const char* path, int* width, int* height, int* channels, char* error, size_t capacity);
// All pixels as floats, top row first, `channels` per pixel.
int fenestra_image_read(void* handle, float* pixels, char* error, size_t capacity);
void fenestra_image_close(void* handle);
// The file's bytes in the format the path's extension names, handed to sink once.
int fenestra_image_encode(const char* path, int width, int height, int channels, const float* pixels,
                          fenestra_image_bytes_sink sink, void* context, char* error, size_t capacity);
}
