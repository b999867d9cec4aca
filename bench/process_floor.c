/* The floor of a whole-process time: a program that does nothing and links nothing beyond the C
   library. bench/whole_process.py starts it as often as each lfcam command it times. */
int main(void) { return 0; }
