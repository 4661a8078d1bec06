// The C ABI boundary: argument checks, status codes and result objects. The only file with extern "C".
int dbrg_api_placeholder;
