pub struct Rind;
