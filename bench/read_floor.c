/* The floor of a command that reads files: read each named file whole into memory and copy it
   once (memcpy), as the least any reader of those bytes must do. bench/whole_process.py times
   it on the same files as the lfcam command it compares. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static volatile char sink;

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    FILE* file = fopen(argv[i], "rb");
    if (!file) {
      fprintf(stderr, "read_floor: cannot open %s\n", argv[i]);
      return 1;
    }
    fseek(file, 0, SEEK_END);
    const long size = ftell(file);
    fseek(file, 0, SEEK_SET);
    char* bytes = malloc(size > 0 ? (size_t)size : 1);
    char* copy = malloc(size > 0 ? (size_t)size : 1);
    if (!bytes || !copy || fread(bytes, 1, (size_t)size, file) != (size_t)size) {
      fprintf(stderr, "read_floor: cannot read %s\n", argv[i]);
      return 1;
    }
    fclose(file);
    memcpy(copy, bytes, (size_t)size);
    if (size > 0) sink = copy[size / 2]; /* keeps the copy from being elided */
    free(bytes);
    free(copy);
  }
  return 0;
}
