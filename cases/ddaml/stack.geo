<?xml version="1.0" standalone="no"?>
<!DOCTYPE DDA SYSTEM "geometry.dtd">
<!-- Three 1 m blocks stacked on a fixed base; the joints overshoot by 0.01 m as DDA input does. -->
<Berkeley:DDA xmlns:Berkeley="http://www.tsoft.com/~bdoolin/dda">
<Berkeley:Geometry>
   <Berkeley:Edgenodedist distance="0.001"/>
   <Jointlist>
      <Joint type="1"> -1 -1 2 -1 </Joint>
      <Joint type="1"> 2 -1 2 0 </Joint>
      <Joint type="1"> 2 0 -1 0 </Joint>
      <Joint type="1"> -1 0 -1 -1 </Joint>
      <Joint type="1"> 0 -0.01 0 3.01 </Joint>
      <Joint type="1"> 1 -0.01 1 3.01 </Joint>
      <Joint type="1"> -0.01 1 1.01 1 </Joint>
      <Joint type="1"> -0.01 2 1.01 2 </Joint>
      <Joint type="1"> -0.01 3 1.01 3 </Joint>
   </Jointlist>
   <Fixedpointlist>
      <Point> 0.5 -0.5 </Point>
      <Point> 1.5 -0.5 </Point>
   </Fixedpointlist>
   <Measuredpointlist>
      <Point> 0.5 2.5 </Point>
      <Point> 0.5 0.5 </Point>
   </Measuredpointlist>
</Berkeley:Geometry>
</Berkeley:DDA>
