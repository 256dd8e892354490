/* placeholder: being written */
typedef int oit_placeholder_dfb;
