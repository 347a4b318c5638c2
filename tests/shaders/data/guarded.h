// Test fixture: a classic include guard around the whole file (comments outside it only).
#ifndef GUARDED_H
#define GUARDED_H

float guarded_value() { return 2.0f; }

#endif  // #ifndef GUARDED_H
