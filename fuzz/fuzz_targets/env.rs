#![no_main]
libfuzzer_sys::fuzz_target!(|data: &[u8]| rouge_fuzz::env(data));
