/* The routing set-up's fragment stage: it writes nothing, since only its
 * stencil writes (each sample's index) matter. */
void main() {}
